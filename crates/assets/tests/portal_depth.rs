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
        .expect_err("a row one sector longer than the walk follows");
    assert_eq!(errors.0.len(), 1, "{errors}");
    let error = &errors.0[0];
    // Both ends start a run of PORTAL_DEPTH_MAX + 1; the one looking back from the last sector
    // is found first: its `portal=` on `  wall bN tN portal=sM`, the sector's fourth wall line.
    let (last, before) = (sectors - 1, sectors - 2);
    let last_sector_line = 2 * (sectors + 1) as u32 + 5 * (sectors as u32 - 1) + 1;
    let portal_column = format!("  wall b{last} t{last} portal=").len() as u32 + 1;
    assert_eq!(
        (error.loc.line, error.loc.col),
        (last_sector_line + 4, portal_column),
        "{error}"
    );
    assert!(
        error.message.contains(&format!(
            "a view from sector 's{last}' can pass {} portals in a row (through sector 's{before}' to sector 's0'), more than the {PORTAL_DEPTH_MAX} the renderer follows",
            last
        )),
        "{error}"
    );
}

/// A corridor that winds back and forth (a serpentine) down the left half of a grid map in
/// `legs` rows of `per_leg` cells, crosses at the bottom, and winds back up the right half:
/// long in sectors, but every straight view turns back. Cells of 32, so it fits the world's
/// limits with more sectors than the walk follows in a row.
fn serpentine_map(legs: usize, per_leg: usize) -> String {
    let width = 2 * per_leg + 3;
    let rows = 2 * legs + 1;
    let mut grid = vec![vec![b'#'; width]; rows];
    let (left, right) = (1, per_leg + 2);
    for leg in 0..legs {
        let row = 2 * leg + 1;
        for column in 0..per_leg {
            grid[row][left + column] = b'.';
            grid[row][right + column] = b'.';
        }
        if leg + 1 < legs {
            // Down the left half: the gaps alternate ends, starting at the right.
            let down = if leg % 2 == 0 {
                left + per_leg - 1
            } else {
                left
            };
            grid[row + 1][down] = b'.';
            // Up the right half from its bottom leg, entered at its left end.
            let from_bottom = legs - 2 - leg;
            let up = if from_bottom.is_multiple_of(2) {
                right + per_leg - 1
            } else {
                right
            };
            grid[row + 1][up] = b'.';
        }
    }
    // The crossing between the halves' bottom legs.
    grid[2 * legs - 1][per_leg + 1] = b'.';
    grid[1][left] = b'@';
    let mut text = String::from(
        "cell 32\nsolid # tex=stone\nopen . floor=0 ceil=64 floor_tex=stone ceil_tex=stone\nplayer @ on=.\ngrid\n",
    );
    for row in grid {
        text += &String::from_utf8(row).expect("ASCII");
        text.push('\n');
    }
    text
}

#[test]
fn a_winding_corridor_of_many_sectors_compiles() {
    // Grid maps merge a straight run into one sector, so this corridor's sectors are its legs
    // and turns: two serpentines of 80 legs are over 300 sectors, more than
    // PORTAL_DEPTH_MAX + 1, and no view passes more than a few portals.
    let text = serpentine_map(80, 6);
    let map = compile_map_str("snake.grid", &text, &catalog()).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        map.sectors.len() > PORTAL_DEPTH_MAX as usize + 1,
        "{}",
        map.sectors.len()
    );
}
