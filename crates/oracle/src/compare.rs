//! Engine frame against oracle frame: counts, edge error, sectors, things, and a diff picture.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::io;
use std::path::Path;

use portalcast::render::surface::Surface;

use crate::Frame;

/// Pixels of a thing the oracle must show for the engine to have missed it when it shows none.
/// A sprite's surface, unlike a wall's, follows its texels' transparency, so a thing the oracle
/// sees in a single pixel is a sub-texel detail (a torch's pole at a distance) whose one pixel
/// flips with a texel edge within rounding of the pixel centre, as texels do on walls (the
/// texel mismatch); two pixels are a thing in view.
pub const MISSED_THING_MIN_PIXELS: usize = 2;

/// How an engine frame differs from the oracle's.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Comparison {
    /// Pixels compared (`width · height`).
    pub pixels: usize,
    /// Pixels whose surface differs from the oracle's (holes included).
    pub surface_mismatches: usize,
    /// Pixels with the oracle's surface but another palette index.
    pub texel_mismatches: usize,
    /// Engine pixels left at [`Surface::None`].
    pub holes: usize,
    /// Over the surface mismatches that are not holes: the largest Chebyshev distance, in
    /// pixels, from the pixel to the nearest oracle pixel of the surface the engine drew there
    /// (1 for an edge one pixel off). A surface the oracle does not show at all counts
    /// `max(width, height)`. 0 when there are no such mismatches.
    pub max_edge_error_px: u32,
    /// The largest vertical error of a wall's edges, in rows: for each column and each wall
    /// surface (a wall, an upper or a lower strip) that both frames show in that column, the
    /// difference between the engine's and the oracle's topmost rows of it, and between their
    /// bottommost rows; the maximum over all of them. 0 when no wall is shown by both.
    pub max_wall_edge_error_px: u32,
    /// Sectors the oracle frame shows (a pixel of their floor, ceiling, one of their walls or
    /// strips, or one of their things) and the engine's does not, ascending.
    pub missed_sectors: Vec<u16>,
    /// Sectors the engine frame shows and the oracle's does not, ascending.
    pub extra_sectors: Vec<u16>,
    /// Things (by index in the map's table) the oracle frame shows in at least
    /// [`MISSED_THING_MIN_PIXELS`] pixels and the engine's in none, ascending: as
    /// [`Comparison::missed_sectors`], for sprites.
    pub missed_things: Vec<u16>,
    /// Things the engine frame shows and the oracle's does not, ascending.
    pub extra_things: Vec<u16>,
}

impl Comparison {
    /// Surface mismatches, in percent of the pixels.
    pub fn surface_mismatch_percent(&self) -> f64 {
        percent(self.surface_mismatches, self.pixels)
    }

    /// Texel mismatches, in percent of all the pixels (not only the matching ones), so the two
    /// percentages add up to the share of pixels that differ at all.
    pub fn texel_mismatch_percent(&self) -> f64 {
        percent(self.texel_mismatches, self.pixels)
    }
}

fn percent(count: usize, total: usize) -> f64 {
    if total == 0 {
        0.0
    } else {
        100.0 * count as f64 / total as f64
    }
}

/// Where a frame differs from the oracle's, per pair of surfaces (`"engine/oracle"`, e.g.
/// `"Wall(3)/Floor(1)"`): the pixel count, the first and last column, the first and last row.
/// For a failing test's message, next to [`write_diff_png`]'s picture.
pub fn mismatch_regions(
    engine_surfaces: &[Surface],
    oracle: &Frame,
) -> BTreeMap<String, (usize, usize, usize, usize, usize)> {
    let mut regions = BTreeMap::<String, (usize, usize, usize, usize, usize)>::new();
    for row in 0..oracle.height {
        for x in 0..oracle.width {
            let engine = engine_surfaces[row * oracle.width + x];
            let reference = oracle.surface(x, row);
            if engine != reference {
                let region = regions
                    .entry(format!("{engine:?}/{reference:?}"))
                    .or_insert((0, x, x, row, row));
                region.0 += 1;
                region.1 = region.1.min(x);
                region.2 = region.2.max(x);
                region.3 = region.3.min(row);
                region.4 = region.4.max(row);
            }
        }
    }
    regions
}

/// Compares an engine frame (surfaces and final palette indices, row-major, the oracle's size)
/// with the oracle's. Sectors of walls and things are taken from `oracle.wall_sectors` and
/// `oracle.thing_sectors`; an engine wall or thing index outside them belongs to no sector (but
/// still counts as a thing the engine shows).
///
/// Panics if the engine slices are not `oracle.width · oracle.height` long.
pub fn compare(engine_surfaces: &[Surface], engine_indices: &[u8], oracle: &Frame) -> Comparison {
    let pixels = oracle.width * oracle.height;
    assert_eq!(
        engine_surfaces.len(),
        pixels,
        "engine surfaces do not match the oracle frame size"
    );
    assert_eq!(
        engine_indices.len(),
        pixels,
        "engine indices do not match the oracle frame size"
    );
    let mut result = Comparison {
        pixels,
        ..Comparison::default()
    };
    // A floor or a ceiling counts as its plane group's: coplanar neighbours are one plane.
    let plane_surfaces = |surfaces: &[Surface]| -> Vec<Surface> {
        surfaces.iter().map(|&s| oracle.plane_surface(s)).collect()
    };
    let (engine_surfaces, oracle_surfaces) = (
        &plane_surfaces(engine_surfaces)[..],
        &plane_surfaces(&oracle.surfaces)[..],
    );
    // Mismatched pixels grouped by the surface the engine drew, one distance map per surface.
    let mut misplaced: HashMap<Surface, Vec<usize>> = HashMap::new();
    let mut engine_sectors = BTreeSet::new();
    let mut oracle_sectors = BTreeSet::new();
    let mut engine_things = BTreeSet::new();
    let mut oracle_things = BTreeSet::new();
    for (pixel, (&engine, &expected)) in engine_surfaces.iter().zip(oracle_surfaces).enumerate() {
        engine_sectors.extend(oracle.sector_of(engine));
        oracle_sectors.extend(oracle.sector_of(expected));
        engine_things.extend(thing_of(engine));
        oracle_things.extend(thing_of(expected));
        if engine == Surface::None {
            result.holes += 1;
        }
        if engine != expected {
            result.surface_mismatches += 1;
            if engine != Surface::None {
                misplaced.entry(engine).or_default().push(pixel);
            }
        } else if engine_indices[pixel] != oracle.indices[pixel] {
            result.texel_mismatches += 1;
        }
    }
    for (surface, pixels) in &misplaced {
        let distances = chebyshev_distances(oracle_surfaces, oracle.width, oracle.height, *surface);
        for &pixel in pixels {
            result.max_edge_error_px = result.max_edge_error_px.max(distances[pixel]);
        }
    }
    result.max_wall_edge_error_px = max_wall_edge_error(
        engine_surfaces,
        oracle_surfaces,
        oracle.width,
        oracle.height,
    );
    result.missed_sectors = oracle_sectors
        .difference(&engine_sectors)
        .copied()
        .collect();
    result.extra_sectors = engine_sectors
        .difference(&oracle_sectors)
        .copied()
        .collect();
    result.missed_things = oracle_things
        .difference(&engine_things)
        .copied()
        .filter(|&thing| {
            let shown = oracle
                .surfaces
                .iter()
                .filter(|&&s| thing_of(s) == Some(thing));
            shown.count() >= MISSED_THING_MIN_PIXELS
        })
        .collect();
    result.extra_things = engine_things.difference(&oracle_things).copied().collect();
    result
}

fn thing_of(surface: Surface) -> Option<u16> {
    match surface {
        Surface::Thing(thing) => Some(thing),
        _ => None,
    }
}

/// How far, in pixels, the two extra oracle renders of [`compare_with_row_tolerance`] move every
/// row's ray up and down: four times the 24.8 rounding step of the engine's rows. An edge the
/// oracle puts closer than this to a row centre is below the engine's row precision: which of
/// the two surfaces the row shows there is a rounding, not an error.
pub const ROW_TOLERANCE_PX: f64 = 1.0 / 128.0;

/// [`compare`] with the oracle's `frame`, except that a sector or a thing counts as missed only
/// if the oracle shows it in `frame` and in both frames rendered with the rows moved by
/// ±[`ROW_TOLERANCE_PX`] (`moved`): a sliver of a sector a pixel high whose only row centre lies
/// within that distance of its edge (a far floor between two steps) is not a missed sector, nor
/// such a sliver of a sprite a missed thing. The other measures are `frame`'s, unchanged.
pub fn compare_with_row_tolerance(
    engine_surfaces: &[Surface],
    engine_indices: &[u8],
    frame: &Frame,
    moved: [&Frame; 2],
) -> Comparison {
    let mut result = compare(engine_surfaces, engine_indices, frame);
    let shown = |frame: &Frame| -> BTreeSet<u16> {
        frame
            .surfaces
            .iter()
            .filter_map(|&surface| frame.sector_of(surface))
            .collect()
    };
    let (up, down) = (shown(moved[0]), shown(moved[1]));
    result
        .missed_sectors
        .retain(|sector| up.contains(sector) && down.contains(sector));
    let things = |frame: &Frame| -> BTreeSet<u16> {
        frame.surfaces.iter().filter_map(|&s| thing_of(s)).collect()
    };
    let (up, down) = (things(moved[0]), things(moved[1]));
    result
        .missed_things
        .retain(|thing| up.contains(thing) && down.contains(thing));
    result
}

/// The row span (topmost, bottommost) of each wall surface in column `x`.
fn wall_rows(
    surfaces: &[Surface],
    width: usize,
    height: usize,
    x: usize,
) -> Vec<(Surface, u32, u32)> {
    let mut spans: Vec<(Surface, u32, u32)> = Vec::new();
    for y in 0..height {
        let surface = surfaces[y * width + x];
        if !matches!(
            surface,
            Surface::Wall(_) | Surface::Upper(_) | Surface::Lower(_)
        ) {
            continue;
        }
        match spans.iter_mut().find(|(s, _, _)| *s == surface) {
            Some((_, _, bottom)) => *bottom = y as u32,
            None => spans.push((surface, y as u32, y as u32)),
        }
    }
    spans
}

/// See [`Comparison::max_wall_edge_error_px`].
fn max_wall_edge_error(engine: &[Surface], oracle: &[Surface], width: usize, height: usize) -> u32 {
    let mut worst = 0;
    for x in 0..width {
        let expected = wall_rows(oracle, width, height, x);
        for (surface, top, bottom) in wall_rows(engine, width, height, x) {
            if let Some(&(_, oracle_top, oracle_bottom)) =
                expected.iter().find(|(s, _, _)| *s == surface)
            {
                worst = worst
                    .max(top.abs_diff(oracle_top))
                    .max(bottom.abs_diff(oracle_bottom));
            }
        }
    }
    worst
}

/// For each pixel, the Chebyshev distance to the nearest pixel showing `surface`, capped at
/// `max(width, height)` (which also stands for "nowhere").
///
/// The two-pass 8-neighbour chamfer with unit weights is exact for the Chebyshev metric.
fn chebyshev_distances(
    surfaces: &[Surface],
    width: usize,
    height: usize,
    surface: Surface,
) -> Vec<u32> {
    let far = width.max(height) as u32;
    let mut d: Vec<u32> = surfaces
        .iter()
        .map(|&s| if s == surface { 0 } else { far })
        .collect();
    for y in 0..height {
        for x in 0..width {
            let mut best = d[y * width + x];
            if x > 0 {
                best = best.min(d[y * width + x - 1] + 1);
            }
            if y > 0 {
                let above = (y - 1) * width;
                best = best.min(d[above + x] + 1);
                if x > 0 {
                    best = best.min(d[above + x - 1] + 1);
                }
                if x + 1 < width {
                    best = best.min(d[above + x + 1] + 1);
                }
            }
            d[y * width + x] = best.min(far);
        }
    }
    for y in (0..height).rev() {
        for x in (0..width).rev() {
            let mut best = d[y * width + x];
            if x + 1 < width {
                best = best.min(d[y * width + x + 1] + 1);
            }
            if y + 1 < height {
                let below = (y + 1) * width;
                best = best.min(d[below + x] + 1);
                if x > 0 {
                    best = best.min(d[below + x - 1] + 1);
                }
                if x + 1 < width {
                    best = best.min(d[below + x + 1] + 1);
                }
            }
            d[y * width + x] = best.min(far);
        }
    }
    d
}

/// A stable false colour for a surface: black for [`Surface::None`], sky blue for the sky,
/// and for the others a colour hashed from the kind and index, tinted by kind (walls reddish,
/// upper strips yellowish, lower strips purplish, floors greenish, ceilings bluish, things
/// bright: every channel at least 160, middles cyan: green and blue at least 160, red below 96)
/// so neighbouring walls still differ.
pub fn surface_colour(surface: Surface) -> [u8; 3] {
    let (kind, index, tint): (u64, u16, [u8; 3]) = match surface {
        Surface::None => return [0, 0, 0],
        Surface::Sky => return [135, 206, 235],
        Surface::Wall(w) => (1, w, [96, 0, 0]),
        Surface::Upper(w) => (2, w, [96, 96, 0]),
        Surface::Lower(w) => (3, w, [96, 0, 96]),
        Surface::Floor(s) => (4, s, [0, 96, 0]),
        Surface::Ceiling(s) => (5, s, [0, 0, 96]),
        Surface::Thing(t) => (6, t, [160, 160, 160]),
        Surface::Middle(w) => (7, w, [0, 160, 160]),
    };
    let hash = splitmix64((kind << 16) | u64::from(index));
    // Things and middles span 96 shades above their tint, the others 160.
    let spread = if kind >= 6 { 96 } else { 160 };
    let channel = |i: usize| tint[i] + (hash >> (8 * i)) as u8 % spread;
    [channel(0), channel(1), channel(2)]
}

fn splitmix64(seed: u64) -> u64 {
    let mut z = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Gap between the panels of the diff picture, in pixels.
const GAP: usize = 4;

/// Writes a PNG for debugging a failed comparison: the engine's surfaces, the oracle's (both in
/// [`surface_colour`]s) and a mismatch mask side by side, with a grey gap between panels. The
/// mask is black where the surfaces agree, red where they differ and yellow for engine holes.
pub fn write_diff_png(engine_surfaces: &[Surface], oracle: &Frame, path: &Path) -> io::Result<()> {
    let (width, height) = (oracle.width, oracle.height);
    assert_eq!(
        engine_surfaces.len(),
        width * height,
        "engine surfaces do not match the oracle frame size"
    );
    let total_width = 3 * width + 2 * GAP;
    let mut image =
        image::RgbImage::from_pixel(total_width as u32, height as u32, image::Rgb([64, 64, 64]));
    for y in 0..height {
        for x in 0..width {
            let engine = oracle.plane_surface(engine_surfaces[y * width + x]);
            let expected = oracle.plane_surface(oracle.surfaces[y * width + x]);
            let mask = if engine == Surface::None {
                [255, 255, 0]
            } else if engine != expected {
                [255, 0, 0]
            } else {
                [0, 0, 0]
            };
            for (panel, colour) in [surface_colour(engine), surface_colour(expected), mask]
                .into_iter()
                .enumerate()
            {
                image.put_pixel(
                    (panel * (width + GAP) + x) as u32,
                    y as u32,
                    image::Rgb(colour),
                );
            }
        }
    }
    image
        .save_with_format(path, image::ImageFormat::Png)
        .map_err(io::Error::other)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chebyshev_distance_is_exact_on_a_small_grid() {
        // One wall pixel at (1, 1) of a 5×3 grid: distances are max(|dx|, |dy|).
        let mut surfaces = vec![Surface::None; 15];
        surfaces[5 + 1] = Surface::Wall(0);
        let d = chebyshev_distances(&surfaces, 5, 3, Surface::Wall(0));
        assert_eq!(d, vec![1, 1, 1, 2, 3, 1, 0, 1, 2, 3, 1, 1, 1, 2, 3]);
        // Absent surface: everything at the cap max(5, 3) = 5.
        let d = chebyshev_distances(&surfaces, 5, 3, Surface::Sky);
        assert!(d.iter().all(|&x| x == 5));
    }

    #[test]
    fn wall_edge_error_is_the_largest_row_difference_of_a_shared_wall() {
        // 3 columns × 6 rows. Column 0: the engine's wall 1 spans rows 1..=3, the oracle's
        // 1..=4 (bottom one row off). Column 1: engine's upper strip of wall 2 rows 0..=1,
        // oracle's rows 2..=3 (top and bottom two rows off). Column 2: only the engine draws
        // wall 5 (a surface mismatch, not an edge error).
        let (width, height) = (3, 6);
        let mut engine = vec![Surface::Floor(0); width * height];
        let mut oracle = engine.clone();
        let paint =
            |frame: &mut [Surface], x: usize, rows: std::ops::RangeInclusive<usize>, s: Surface| {
                for y in rows {
                    frame[y * width + x] = s;
                }
            };
        paint(&mut engine, 0, 1..=3, Surface::Wall(1));
        paint(&mut oracle, 0, 1..=4, Surface::Wall(1));
        paint(&mut engine, 1, 0..=1, Surface::Upper(2));
        paint(&mut oracle, 1, 2..=3, Surface::Upper(2));
        paint(&mut engine, 2, 0..=5, Surface::Wall(5));
        assert_eq!(max_wall_edge_error(&engine, &oracle, width, height), 2);
        assert_eq!(max_wall_edge_error(&oracle, &oracle, width, height), 0);
        let frame = Frame {
            width,
            height,
            surfaces: oracle.clone(),
            indices: vec![0; width * height],
            depths: vec![1.0; width * height],
            wall_sectors: vec![0; 8],
            thing_sectors: Vec::new(),
            plane_groups: Vec::new(),
        };
        let result = compare(&engine, &vec![0; width * height], &frame);
        assert_eq!(result.max_wall_edge_error_px, 2);
    }

    #[test]
    fn surface_colours_are_stable_and_distinct() {
        assert_eq!(surface_colour(Surface::None), [0, 0, 0]);
        assert_eq!(
            surface_colour(Surface::Wall(3)),
            surface_colour(Surface::Wall(3))
        );
        assert_ne!(
            surface_colour(Surface::Wall(3)),
            surface_colour(Surface::Wall(4))
        );
        assert_ne!(
            surface_colour(Surface::Floor(3)),
            surface_colour(Surface::Ceiling(3))
        );
    }
}
