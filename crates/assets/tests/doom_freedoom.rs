//! The Doom importer's first part on real maps: Freedoom's E1M1 (Phase 1) and MAP01 (Phase 2),
//! from Debian's `freedoom` package, cut into convex cells by Debian's `glbsp` (both installed
//! by `cargo xtest`'s setup). Checks the facts issue 19 gives for them, that every GL subsector
//! makes a closed convex cell facing one sector with its portals paired, and measures what
//! rounding the node builder's fractional vertices does to their convexity.

use std::path::{Path, PathBuf};

use portalcast_assets::doom::{self, Cell, CellWall, DoomLevel, GlNodes, Wad};

const FREEDOOM: &str = "/usr/share/games/doom";

fn wad_path(name: &str) -> PathBuf {
    let path = Path::new(FREEDOOM).join(name);
    assert!(
        path.is_file(),
        "{} is missing: install Debian's freedoom package (`cargo xtest` does)",
        path.display()
    );
    path
}

fn scratch() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("doom")
}

/// The map, its GL nodes and its cells.
fn import(wad_name: &str, map: &str) -> (DoomLevel, GlNodes, Vec<Cell>) {
    let path = wad_path(wad_name);
    let wad = Wad::open(&path).unwrap_or_else(|e| panic!("{e}"));
    let level = DoomLevel::read(&wad, map).unwrap_or_else(|e| panic!("{e}"));
    let gwa = doom::build_gwa(&path, &scratch().join(map)).unwrap_or_else(|e| panic!("{e}"));
    let gwa = Wad::open(&gwa).unwrap_or_else(|e| panic!("{e}"));
    let nodes = GlNodes::read(&gwa, map, &level.vertices).unwrap_or_else(|e| panic!("{e}"));
    let cells = doom::cells(&level, &nodes).unwrap_or_else(|e| panic!("{map}: {e:?}"));
    (level, nodes, cells)
}

/// Every portal and opening leads to a cell with a wall back, along the same two vertices.
fn assert_portals_pair(map: &str, cells: &[Cell]) {
    for (index, cell) in cells.iter().enumerate() {
        for (offset, wall) in cell.walls.iter().enumerate() {
            let (CellWall::Portal { cell: other, .. } | CellWall::Open { cell: other }) = wall
            else {
                continue;
            };
            let (a, b) = (
                cell.outline[offset],
                cell.outline[(offset + 1) % cell.outline.len()],
            );
            let behind = &cells[*other as usize];
            let back = (0..behind.outline.len()).any(|at| {
                let (c, d) = (behind.outline[at], behind.outline[(at + 1) % behind.outline.len()]);
                let leads_back = matches!(behind.walls[at], CellWall::Portal { cell, .. } | CellWall::Open { cell } if cell as usize == index);
                leads_back && (c, d) == (b, a)
            });
            assert!(
                back,
                "{map}: cell {index}'s wall {offset} into cell {other} has no wall back"
            );
        }
    }
}

/// With the vertices rounded to `bits` fraction bits: how many cells get a wall of zero length,
/// how many turn against their winding by more than `tolerance` map units, and the deepest such
/// turn.
fn bent_at(cells: &[Cell], bits: u32, tolerance: f64) -> (usize, usize, f64) {
    let depths: Vec<Option<f64>> = cells
        .iter()
        .map(|cell| doom::reflex_depth(&cell.outline, bits))
        .collect();
    let zero = depths.iter().filter(|depth| depth.is_none()).count();
    let bent = depths
        .iter()
        .flatten()
        .filter(|&&depth| depth > tolerance)
        .count();
    let deepest = depths.iter().flatten().fold(0f64, |a, &b| a.max(b));
    (zero, bent, deepest)
}

/// One 16.16 step: the node builder's own rounding of the vertices it makes.
const BUILDER_ROUNDING: f64 = 1.0 / 65536.0;

/// Prints what rounding the vertices to 24.8 and to whole units does to the cells, and checks
/// the cells as built: convex up to the builder's rounding, no wall of zero length.
fn report_rounding(map: &str, cells: &[Cell]) {
    for (bits, name) in [(16, "16.16 (as built)"), (8, "24.8"), (0, "whole units")] {
        let (zero, bent, deepest) = bent_at(cells, bits, 2.0 * BUILDER_ROUNDING);
        println!(
            "{map} in {name}: {zero} cells with a zero-length wall, {bent} bent beyond the builder's rounding, deepest {deepest:.5} units"
        );
    }
    let (zero, bent, _) = bent_at(cells, 16, 2.0 * BUILDER_ROUNDING);
    assert_eq!(
        (zero, bent),
        (0, 0),
        "{map}: the node builder's cells are convex"
    );
    // What the importer's vertex format rests on: in 24.8 no wall vanishes and no cell bends by
    // as much as one 24.8 step; in whole units walls vanish.
    let (zero, _, deepest) = bent_at(cells, 8, 0.0);
    assert!(
        zero == 0 && deepest < 1.0 / 256.0,
        "{map} in 24.8: {zero} zero-length walls, {deepest} deep"
    );
    assert!(
        bent_at(cells, 0, 0.0).0 > 0,
        "{map}: whole units keep every wall"
    );
}

#[test]
fn freedoom_e1m1_makes_closed_convex_cells_with_paired_portals() {
    let (level, nodes, cells) = import("freedoom1.wad", "E1M1");
    assert_eq!(level.sectors.len(), 133);
    assert_eq!(level.linedefs.len(), 812);
    assert_eq!(level.linedefs.iter().filter(|l| l.two_sided()).count(), 442);
    assert_eq!(nodes.subsectors.len(), 509);
    assert_eq!(cells.len(), 509);
    assert_portals_pair("E1M1", &cells);
    let fractional = nodes
        .segs
        .iter()
        .flat_map(|seg| [seg.start, seg.end])
        .filter(|v| v.x & 0xFFFF != 0 || v.y & 0xFFFF != 0)
        .collect::<std::collections::HashSet<_>>()
        .len();
    println!("E1M1: {fractional} vertices with a fraction");
    assert_eq!(fractional, 154, "issue 19's count");
    report_rounding("E1M1", &cells);
}

#[test]
fn freedoom_2_map01_makes_closed_convex_cells_with_paired_portals() {
    let (level, nodes, cells) = import("freedoom2.wad", "MAP01");
    assert_eq!(level.sectors.len(), 198);
    assert_eq!(nodes.subsectors.len(), 592);
    assert_portals_pair("MAP01", &cells);
    report_rounding("MAP01", &cells);
}

#[test]
fn a_missing_map_names_the_maps_the_wad_has() {
    let wad = Wad::open(&wad_path("freedoom1.wad")).unwrap();
    let error = DoomLevel::read(&wad, "E9M9").unwrap_err().to_string();
    assert!(
        error.contains("has no map E9M9: its maps are E1M1, E1M2"),
        "{error}"
    );
}

#[test]
fn a_missing_wad_says_what_to_do() {
    let error = Wad::open(Path::new("/nonexistent/doom.wad"))
        .unwrap_err()
        .to_string();
    assert!(
        error.starts_with("/nonexistent/doom.wad: cannot read it"),
        "{error}"
    );
}

/// The names `level`'s sidedefs and sectors use: wall textures, then flats (`-`: none).
fn used_names(level: &DoomLevel) -> (Vec<String>, Vec<String>) {
    let mut textures: Vec<String> = level
        .sidedefs
        .iter()
        .flat_map(|side| [&side.upper, &side.lower, &side.middle])
        .filter(|name| name.as_str() != "-")
        .cloned()
        .collect();
    textures.sort();
    textures.dedup();
    let mut flats: Vec<String> = level
        .sectors
        .iter()
        .flat_map(|sector| [&sector.floor_flat, &sector.ceiling_flat])
        .cloned()
        .collect();
    flats.sort();
    flats.dedup();
    (textures, flats)
}

#[test]
fn freedoom_e1m1_s_textures_compose_and_its_flats_and_light_tables_read() {
    let wad = Wad::open(&wad_path("freedoom1.wad")).unwrap();
    let level = DoomLevel::read(&wad, "E1M1").unwrap();
    let palette = doom::palette(&wad).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(palette[0], [0, 0, 0], "Doom's palette starts with black");
    assert_eq!(
        doom::colormaps(&wad).unwrap().len(),
        34,
        "32 light rows, invulnerability, black"
    );
    let textures = doom::Textures::read(&wad).unwrap_or_else(|e| panic!("{e}"));
    let (used, flats) = used_names(&level);
    let mut odd_sizes = Vec::new();
    for name in &used {
        let image = textures
            .compose(&wad, name)
            .unwrap_or_else(|e| panic!("{e}"));
        if !image.width.is_power_of_two() || !image.height.is_power_of_two() {
            odd_sizes.push(format!("{name} {}x{}", image.width, image.height));
        }
    }
    println!(
        "E1M1: {} wall textures, {} flats; not powers of two: {odd_sizes:?}",
        used.len(),
        flats.len()
    );
    // Issue 19's facts: four textures of E1M1 are not powers of two in one side.
    assert_eq!(
        odd_sizes,
        [
            "COMPUTE2 256x56",
            "DOOR1 64x72",
            "EXITDOOR 128x72",
            "MIDBARS3 64x72"
        ]
    );
    let bars = textures.compose(&wad, "MIDBARS3").unwrap();
    assert!(bars.gaps() > 0, "a see-through middle texture has gaps");
    for name in &flats {
        let flat = doom::flat(&wad, name).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((flat.width, flat.height, flat.gaps()), (64, 64, 0));
    }
    assert!(flats.iter().any(|name| name == "F_SKY1"), "E1M1 has sky");
    let error = textures.compose(&wad, "NOSUCHTX").unwrap_err().to_string();
    assert!(
        error.contains("lump NOSUCHTX: is not a texture of this WAD"),
        "{error}"
    );
}
