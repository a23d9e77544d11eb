//! Room over room: the floor and ceiling portals between sectors of different layers
//! (`ceil_portal=`, `floor_portal=`, `layer=`; docs/MAP_FORMAT.md, "Room over room").
//!
//! Two linked sectors are one vertical column cut at one height: the same outline, on
//! different layers, the lower one's flat ceiling at the upper one's flat floor. The renderer
//! continues a view through the cut (the window the plane leaves on screen), the player's body
//! crosses it, and neither needs more than the pair.

use portalcast_format::{LayerLink, NO_LINK};

use crate::diag::Located;
use crate::geometry::{cross, Point};
use crate::source::SourceMap;

/// Every sector's [`LayerLink`] (empty when no sector has a floor or ceiling portal), after
/// checking each link: `ceil_portal=` and `floor_portal=` agree, the two sectors differ in
/// layer, have the same corners (`corners`, each sector's outline clockwise) and meet at one
/// flat height, and neither moves. `sloped[i]` is `(floor, ceiling)` of sector `i`: whether
/// each slopes.
pub(crate) fn check_links(
    source: &SourceMap,
    corners: &[Vec<Point>],
    sloped: &[(bool, bool)],
    errors: &mut Vec<Located>,
) -> Vec<LayerLink> {
    let sectors = &source.sectors;
    if sectors
        .iter()
        .all(|sector| sector.above.is_none() && sector.below.is_none())
    {
        return Vec::new();
    }
    let mut links = vec![
        LayerLink {
            above: NO_LINK,
            below: NO_LINK,
        };
        sectors.len()
    ];
    let before = errors.len();
    // Where each sector's ceiling portal is written (the first place naming the link).
    let mut written = vec![None; sectors.len()];
    // Each link as (lower, upper, where it is written), from either end.
    let mut pairs = Vec::new();
    for (index, sector) in sectors.iter().enumerate() {
        if let Some(above) = &sector.above {
            pairs.push((index, above.value, above.loc));
        }
        if let Some(below) = &sector.below {
            pairs.push((below.value, index, below.loc));
        }
    }
    for &(lower, upper, loc) in &pairs {
        let (low, high) = (&sectors[lower], &sectors[upper]);
        if lower == upper {
            errors.push((
                loc,
                format!("{} opens into itself; a floor or ceiling portal names another sector, on another layer", low.label),
            ));
            continue;
        }
        let (was_above, was_below) = (links[lower].above, links[upper].below);
        if was_above != NO_LINK && usize::from(was_above) != upper {
            errors.push((
                loc,
                format!(
                    "the ceiling of {} opens into both {} and {}; a ceiling opens into one sector, so remove one portal",
                    low.label, sectors[usize::from(was_above)].label, high.label
                ),
            ));
            continue;
        }
        if was_below != NO_LINK && usize::from(was_below) != lower {
            errors.push((
                loc,
                format!(
                    "the floor of {} opens into both {} and {}; a floor opens into one sector, so remove one portal",
                    high.label, sectors[usize::from(was_below)].label, low.label
                ),
            ));
            continue;
        }
        if was_above != NO_LINK {
            // The same link written at both ends: checked once.
            continue;
        }
        links[lower].above = upper as u16;
        links[upper].below = lower as u16;
        written[lower] = Some(loc);
    }
    // Ceilings that open, followed upwards, must end: a loop is no stack of rooms.
    let mut in_loop = vec![false; sectors.len()];
    for start in 0..sectors.len() {
        let mut at = start;
        for _ in 0..sectors.len() {
            match links[at].above {
                NO_LINK => break,
                above => at = usize::from(above),
            }
            if at == start {
                in_loop[start] = true;
                break;
            }
        }
        if in_loop[start] && !in_loop[..start].iter().any(|&seen| seen) {
            errors.push((
                written[start].unwrap_or(sectors[start].loc),
                format!(
                    "the floor and ceiling portals from {} lead round in a loop back to it; layers stack one above another, so remove one of the portals",
                    sectors[start].label
                ),
            ));
        }
    }
    for &(lower, upper, loc) in &pairs {
        if in_loop[lower] || written[lower] != Some(loc) {
            continue;
        }
        let (low, high) = (&sectors[lower], &sectors[upper]);
        if low.layer.value == high.layer.value {
            errors.push((
                loc,
                format!(
                    "{} and {} are both on layer {}; sectors linked through a floor or ceiling are on different layers, so give one of them another layer=",
                    low.label, high.label, low.layer.value
                ),
            ));
        }
        if !same_outline(&corners[lower], &corners[upper]) {
            errors.push((
                loc,
                format!(
                    "{} and {} do not have the same corners; a floor or ceiling portal joins two sectors with the same outline, one above the other, so give both the same corner points",
                    low.label, high.label
                ),
            ));
        }
        if sloped[lower].1 || sloped[upper].0 {
            errors.push((
                loc,
                format!(
                    "the ceiling of {} or the floor of {} slopes; the two meet at a floor or ceiling portal, which is flat, so make both flat",
                    low.label, high.label
                ),
            ));
        } else if low.ceil.value != high.floor.value {
            errors.push((
                loc,
                format!(
                    "the ceiling of {} is at {} and the floor of {} at {}; linked sectors meet at one height, so make them equal",
                    low.label, low.ceil.value, high.label, high.floor.value
                ),
            ));
        }
        for sector in [low, high] {
            if let Some(mover) = &sector.mover {
                errors.push((
                    loc,
                    format!(
                        "{} moves ({}) and is linked to another layer; a sector with a floor or ceiling portal cannot move, so remove one",
                        sector.label,
                        mover.kind.name()
                    ),
                ));
            }
        }
    }
    if errors.len() > before {
        return Vec::new();
    }
    links
}

/// Whether two convex clockwise outlines have the same corners, in the same order: the points
/// where the outline turns (a vertex between collinear walls is not a corner).
fn same_outline(a: &[Point], b: &[Point]) -> bool {
    let (a, b) = (turning_points(a), turning_points(b));
    if a.len() != b.len() || a.is_empty() {
        return false;
    }
    let Some(shift) = b.iter().position(|&p| p == a[0]) else {
        return false;
    };
    (0..a.len()).all(|i| a[i] == b[(i + shift) % b.len()])
}

/// The points of `outline` where it turns.
fn turning_points(outline: &[Point]) -> Vec<Point> {
    let n = outline.len();
    (0..n)
        .filter(|&i| {
            let (before, here, after) =
                (outline[(i + n - 1) % n], outline[i], outline[(i + 1) % n]);
            cross(before, here, after) != 0
        })
        .map(|i| outline[i])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outlines_match_from_any_corner_and_over_split_walls() {
        let square = [(0, 0), (0, 64), (64, 64), (64, 0)];
        let turned = [(64, 64), (64, 0), (0, 0), (0, 64)];
        let split = [(0, 0), (0, 32), (0, 64), (64, 64), (64, 0)];
        let other = [(0, 0), (0, 64), (64, 64), (72, 0)];
        assert!(same_outline(&square, &turned));
        assert!(same_outline(&square, &split));
        assert!(!same_outline(&square, &other));
    }
}
