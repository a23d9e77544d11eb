//! The player's body a map gives (`player … eye= height= step=`): its defaults, both formats,
//! and the errors of a bad one (the bad maps `player_*.map` in `tests/bad/`).

use portalcast_assets::{compile_map_str, Catalog};
use portalcast_format::PlayerSize;

fn catalog() -> Catalog {
    Catalog::new(["brick", "stone"], [] as [&str; 0], false)
}

fn text_map(player: &str) -> String {
    format!(
        "vertex a 0 0\nvertex b 128 0\nvertex c 128 128\nvertex d 0 128\n\
         sector s floor=0 ceil=128 floor_tex=stone ceil_tex=stone\n\
         wall a b tex=brick\nwall b c tex=brick\nwall c d tex=brick\nwall d a tex=brick\n\
         {player}\n"
    )
}

fn grid_map(player: &str) -> String {
    format!(
        "cell 64\nsolid # tex=brick\nopen . floor=0 ceil=128 floor_tex=stone ceil_tex=stone\n\
         {player}\ngrid\n####\n#@.#\n####\n"
    )
}

fn size_of(file: &str, text: &str) -> PlayerSize {
    compile_map_str(file, text, &catalog())
        .unwrap_or_else(|errors| panic!("{errors}"))
        .player_start
        .size
}

#[test]
fn a_map_without_body_keys_has_the_native_body() {
    assert_eq!(
        size_of("room.map", &text_map("player 64 64")),
        PlayerSize::NATIVE
    );
    assert_eq!(
        size_of("room.grid", &grid_map("player @ on=.")),
        PlayerSize::NATIVE
    );
}

#[test]
fn both_formats_take_the_body_from_the_player_line() {
    let doom = "eye=41 height=56 step=24";
    assert_eq!(
        size_of("room.map", &text_map(&format!("player 64 64 {doom}"))),
        PlayerSize::DOOM
    );
    assert_eq!(
        size_of("room.grid", &grid_map(&format!("player @ on=. {doom}"))),
        PlayerSize::DOOM
    );
    // The height defaults to the eye plus the native headroom, the step to the native one.
    assert_eq!(
        size_of("room.map", &text_map("player 64 64 eye=24")),
        PlayerSize {
            eye_height: 24,
            height: 40,
            step_up: 16
        }
    );
}

#[test]
fn a_grid_reports_a_bad_body_at_its_value() {
    let errors = compile_map_str("room.grid", &grid_map("player @ on=. step=80"), &catalog())
        .expect_err("a step over 64 is refused");
    let text = errors.to_string();
    assert!(
        text.contains("4:20: step 80 is out of range; use 0..=64"),
        "{text}"
    );
}
