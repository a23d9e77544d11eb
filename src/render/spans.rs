//! Turns per-column windows into horizontal spans, the way Doom's `R_MakeSpans` does: a row's
//! span starts where the row enters the window and ends where it leaves, so every pixel of every
//! window is in exactly one span and no span covers a pixel outside the windows.

pub use crate::raster::Window;

/// Emits the spans of `windows` (one per column, the first at column `first_column`) as
/// `emit(row, x_start, x_end)` with `x_end` exclusive. `span_start` is scratch, one entry per
/// screen row (at least as many as the largest `bottom`).
pub fn make_spans(
    windows: &[Window],
    first_column: usize,
    span_start: &mut [i16],
    mut emit: impl FnMut(usize, usize, usize),
) {
    let mut old = Window::EMPTY;
    // The column before's window as stored, as a word (`old` is it normalised: an empty window
    // is EMPTY).
    let mut stored_before = Window::EMPTY.word();
    let mut x = first_column;
    for &window in windows {
        // Most columns have the window of the column before: no span ends or starts there,
        // and the scan moves on after one word compare.
        if window.word() != stored_before {
            stored_before = window.word();
            let new = if window.is_empty() {
                Window::EMPTY
            } else {
                window
            };
            if new != old {
                change_rows(old, new, x, span_start, &mut emit);
                old = new;
            }
        }
        x += 1;
    }
    change_rows(old, Window::EMPTY, x, span_start, &mut emit);
}

/// Column `x`'s window is `new` where the column before had `old` (both normalised: an empty
/// window is [`Window::EMPTY`]): ends the spans of the rows that leave and starts those of the
/// rows that enter.
#[inline(always)]
fn change_rows(
    old: Window,
    new: Window,
    x: usize,
    span_start: &mut [i16],
    emit: &mut impl FnMut(usize, usize, usize),
) {
    let (mut top, mut bottom) = (old.top, old.bottom);
    let outside = |row: i16| row < new.top || row >= new.bottom;
    // Rows that leave the window end their span at this column.
    while top < bottom && outside(top) {
        emit(top as usize, span_start[top as usize] as usize, x);
        top += 1;
    }
    while bottom > top && outside(bottom - 1) {
        bottom -= 1;
        emit(bottom as usize, span_start[bottom as usize] as usize, x);
    }
    // Rows that enter start a span here; what remains of the old window is inside the new.
    if new.is_empty() {
        return;
    }
    if top >= bottom {
        top = new.bottom;
        bottom = new.bottom;
    }
    for row in new.top..top {
        span_start[row as usize] = x as i16;
    }
    for row in bottom..new.bottom {
        span_start[row as usize] = x as i16;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn coverage(windows: &[Window], height: usize) -> Vec<Vec<u32>> {
        let mut counts = vec![vec![0u32; windows.len()]; height];
        let mut scratch = vec![0i16; height];
        make_spans(windows, 0, &mut scratch, |row, start, end| {
            assert!(start < end, "empty span on row {row}");
            for count in &mut counts[row][start..end] {
                *count += 1;
            }
        });
        counts
    }

    fn check(windows: &[Window], height: usize) {
        let counts = coverage(windows, height);
        for (x, window) in windows.iter().enumerate() {
            for (row, row_counts) in counts.iter().enumerate() {
                let inside = !window.is_empty()
                    && (window.top as usize..window.bottom as usize).contains(&row);
                assert_eq!(
                    row_counts[x],
                    u32::from(inside),
                    "column {x} row {row} of {windows:?}"
                );
            }
        }
    }

    #[test]
    fn staircase_and_gaps_cover_every_pixel_once() {
        let w = |top, bottom| Window { top, bottom };
        check(
            &[
                w(2, 6),
                w(3, 7),
                w(0, 2),
                Window::EMPTY,
                w(4, 5),
                w(1, 8),
                w(1, 8),
                w(6, 3),
            ],
            8,
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        #[test]
        fn any_windows_cover_every_pixel_exactly_once(
            raw in proptest::collection::vec((0i16..20, 0i16..20), 0..40)
        ) {
            let windows: Vec<Window> = raw.into_iter().map(|(top, bottom)| Window { top, bottom }).collect();
            check(&windows, 20);
        }
    }
}
