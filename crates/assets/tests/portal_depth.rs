//! The portal depth rule (issue 16, defect 6b): a map where a view can pass more portals in a
//! row than the renderer follows (`PORTAL_DEPTH_MAX`, the walk's `MAX_PORTAL_DEPTH`) is refused
//! at the first portal of the longest run; runs that turn back, however long the map, pass.

use portalcast_assets::{compile_map_str, Catalog};
use portalcast_format::limits::PORTAL_DEPTH_MAX;

fn catalog() -> Catalog {
    Catalog::new(["stone"], Vec::<String>::new(), false)
}

/// `count` sectors 16 wide in a row along x (the first reaching back to x = -16 so that the
/// start, at x = 0, is 16 from the wall behind it), each a portal to the next.
fn row_map(count: usize) -> String {
    let mut text = String::new();
    let x = |i: usize| if i == 0 { -16 } else { 16 * i as i64 };
    for i in 0..=count {
        text += &format!("vertex t{i} {} 0\nvertex b{i} {} 128\n", x(i), x(i));
    }
    for i in 0..count {
        let j = i + 1;
        text += &format!("sector s{i} floor=0 ceil=128 floor_tex=stone ceil_tex=stone\n");
        text += &format!("  wall t{i} t{j} tex=stone\n");
        if j < count {
            text += &format!("  wall t{j} b{j} portal=s{j}\n");
        } else {
            text += &format!("  wall t{j} b{j} tex=stone\n");
        }
        text += &format!("  wall b{j} b{i} tex=stone\n");
        if i > 0 {
            text += &format!("  wall b{i} t{i} portal=s{}\n", i - 1);
        } else {
            text += &format!("  wall b{i} t{i} tex=stone\n");
        }
    }
    text + "player 0 64\n"
}

#[test]
fn a_row_the_renderer_follows_whole_compiles() {
    // PORTAL_DEPTH_MAX + 1 sectors: depth 0 to PORTAL_DEPTH_MAX, the extreme map `chain`.
    let sectors = PORTAL_DEPTH_MAX as usize + 1;
    compile_map_str("row.map", &row_map(sectors), &catalog()).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_row_one_deeper_is_refused_at_a_portal_of_the_run() {
    let sectors = PORTAL_DEPTH_MAX as usize + 2;
    let errors = compile_map_str("row.map", &row_map(sectors), &catalog())
        .expect_err("a row of 66 sectors is deeper than the walk follows");
    assert_eq!(errors.0.len(), 1, "{errors}");
    let error = &errors.0[0];
    // Both ends start a run of 65; the one looking back from the last sector is found first:
    // its `portal=` on `  wall b65 t65 portal=s64`, the sector's fourth wall line.
    let last_sector_line = 2 * (sectors + 1) as u32 + 5 * (sectors as u32 - 1) + 1;
    assert_eq!(
        (error.loc.line, error.loc.col),
        (last_sector_line + 4, 23),
        "{error}"
    );
    assert!(
        error.message.contains(
            "a view from sector 's65' can pass 65 portals in a row (through sector 's64' to sector 's0'), more than the 64 the renderer follows"
        ),
        "{error}"
    );
}

/// A corridor of `legs` rows of `per_leg` sectors, joined at alternate ends so that it winds
/// back and forth (a serpentine): long in sectors, but every straight view turns back.
fn serpentine_map(legs: usize, per_leg: usize) -> String {
    // Cells of 32 x 32 on a grid map: rows of open cells separated by solid rows, with a gap at
    // alternate ends.
    let width = per_leg + 2;
    let mut text = String::from(
        "cell 32\nsolid # tex=stone\nopen . floor=0 ceil=64 floor_tex=stone ceil_tex=stone\nplayer @ on=.\ngrid\n",
    );
    text += &"#".repeat(width);
    text.push('\n');
    for leg in 0..legs {
        let mut row = String::from("#");
        for column in 0..per_leg {
            row.push(if leg == 0 && column == 0 { '@' } else { '.' });
        }
        row.push('#');
        text += &row;
        text.push('\n');
        if leg + 1 < legs {
            let gap = if leg % 2 == 0 { per_leg } else { 1 };
            let wall: String = (0..width)
                .map(|c| if c == gap { '.' } else { '#' })
                .collect();
            text += &wall;
            text.push('\n');
        }
    }
    text += &"#".repeat(width);
    text + "\n"
}

#[test]
fn a_winding_corridor_of_many_sectors_compiles() {
    // Grid maps merge a straight run into one sector, so this corridor's sectors are its legs
    // and turns: 2 legs of 40 cells and the turn between are 3 sectors; a serpentine of 80
    // legs is 159, more than PORTAL_DEPTH_MAX + 1, and no view passes more than a few portals.
    let text = serpentine_map(80, 6);
    let map = compile_map_str("snake.grid", &text, &catalog()).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        map.sectors.len() > PORTAL_DEPTH_MAX as usize + 1,
        "{}",
        map.sectors.len()
    );
}
