//! Things: the words of a `thing` line compile to the right fields, the checks against the
//! sprite's size run where the images are known, and the per-map limit holds.

mod common;

use common::{sprite, valid_assets};
use image::RgbaImage;
use portalcast_assets::{compile_dir, compile_map_str, Catalog};
use portalcast_format::limits::THINGS_MAX;
use portalcast_format::{Thing, THING_HANGING, THING_SOLID};

/// Two rooms side by side (0..128 and 128..256, floor 0, ceiling 96), the player in the first.
fn two_rooms(things: &str) -> String {
    format!(
        "vertex a 0 0\nvertex b 128 0\nvertex c 128 128\nvertex d 0 128\n\
         vertex e 256 0\nvertex f 256 128\n\
         sector west floor=0 ceil=96 floor_tex=stone ceil_tex=stone\n\
         wall a b tex=brick\nwall b c portal=east lower=brick\nwall c d tex=brick\nwall d a tex=brick\n\
         sector east floor=8 ceil=104 floor_tex=stone ceil_tex=stone\n\
         wall b e tex=brick\nwall e f tex=brick\nwall f c tex=brick\nwall c b portal=west upper=brick\n\
         player 64 64\n{things}"
    )
}

fn catalog() -> Catalog {
    Catalog::new(["brick", "stone"], ["lamp", "torch"], false)
        .with_sprite_size("torch", 16, 48)
        .with_sprite_size("lamp", 15, 24)
}

fn things(file_name: &str, text: &str) -> Vec<Thing> {
    compile_map_str(file_name, text, &catalog())
        .unwrap_or_else(|e| panic!("{e}"))
        .things
}

#[test]
fn thing_words_compile_to_its_fields() {
    let found = things(
        "rooms.map",
        &two_rooms(
            "thing torch 200 64 solid\n\
             thing lamp 64 32 z=8 hang angle=90\n\
             thing torch 32 96 radius=12 z=4\n\
             thing lamp 96 96 hang solid radius=9\n",
        ),
    );
    // Grouped by sector: the west room's three, its solid one first and the others in file
    // order, then the east room's one.
    let fields: Vec<(i32, u16, i16, u16, u16)> = found
        .iter()
        .map(|t| (t.x_fx8 / 256, t.sector, t.z, t.radius, t.flags))
        .collect();
    assert_eq!(
        fields,
        [
            (96, 0, 0, 9, THING_HANGING | THING_SOLID),
            // Lamp: 15 wide, so the radius is 8 (half the width, rounded up).
            (64, 0, 8, 8, THING_HANGING),
            (32, 0, 4, 12, 0),
            (200, 1, 0, 8, THING_SOLID),
        ]
    );
    assert_eq!(found[1].angle, 16384);
}

#[test]
fn grid_thing_words_compile_to_its_fields() {
    let text = "cell 64\nsolid # tex=brick\n\
                open . floor=0 ceil=128 floor_tex=stone ceil_tex=stone\n\
                player @ on=. angle=0\n\
                thing l lamp on=. hang z=16 solid\n\
                thing t torch radius=20 on=.\n\
                grid\n#####\n#@.l#\n#t..#\n#####\n";
    let found = things("rooms.grid", text);
    let fields: Vec<(i16, u16, u16)> = found.iter().map(|t| (t.z, t.radius, t.flags)).collect();
    assert_eq!(
        fields,
        [(16, 8, THING_HANGING | THING_SOLID), (0, 20, 0)],
        "{found:?}"
    );
}

#[test]
fn things_exactly_fitting_pass() {
    // The torch (16×48) with its footprint touching the walls, standing under the ceiling, and
    // hanging down to the floor of a room 96 tall.
    let found = things(
        "fit.map",
        &two_rooms("thing torch 8 8 z=48\nthing torch 120 120 hang z=48\n"),
    );
    assert_eq!(found.len(), 2);
}

#[test]
fn a_sprite_without_a_size_counts_as_zero_by_zero() {
    let catalog = Catalog::new(["brick", "stone"], ["torch"], false);
    let map = compile_map_str("rooms.map", &two_rooms("thing torch 1 1 z=96\n"), &catalog)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((map.things[0].radius, map.things[0].z), (0, 96));
}

#[test]
fn more_things_than_a_map_holds_is_one_error_at_the_first_beyond() {
    let count = THINGS_MAX as usize + 2;
    let lines: String = (0..count)
        .map(|i| format!("thing torch {} {}\n", 10 + i % 100, 10 + i / 100))
        .collect();
    let text = two_rooms(&lines);
    let first_line = text.lines().count() - count + 1;
    let errors = compile_map_str("many.map", &text, &catalog()).expect_err("too many things");
    assert_eq!(errors.0.len(), 1, "{errors}");
    let error = &errors.0[0];
    assert_eq!(
        (error.loc.line as usize, error.loc.col),
        (first_line + THINGS_MAX as usize, 1)
    );
    assert!(
        error.message.contains(&format!(
            "the map has {count} things, more than the {THINGS_MAX} a map may hold"
        )),
        "{errors}"
    );
    // THINGS_MAX itself compiles.
    let lines: String = (0..THINGS_MAX as usize)
        .map(|i| format!("thing torch {} {}\n", 10 + i % 100, 10 + i / 100))
        .collect();
    let map = compile_map_str("many.map", &two_rooms(&lines), &catalog())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.sector_things.last().copied(), Some(THINGS_MAX as u16));
}

#[test]
fn an_asset_directory_checks_things_against_the_sprite_images() {
    // The common sprite is 8×12: radius 4 at least.
    let scratch = valid_assets("thing_radius", "stone");
    let map = common::room_map("stone").replace("thing torch 32 32", "thing torch 32 32 radius=3");
    scratch.write("maps/room.map", map.as_bytes());
    assert_eq!(
        scratch.only_error(),
        "maps/room.map:11:26: radius=3 is less than half the width of the sprite (8); use radius=4 or more, or leave radius= out (the default is 4)"
    );
    // 12 tall, 90 above the floor of a room 96 tall.
    let map = common::room_map("stone").replace("thing torch 32 32", "thing torch 32 32 z=90");
    scratch.write("maps/room.map", map.as_bytes());
    assert_eq!(
        scratch.only_error(),
        "maps/room.map:11:1: thing 'torch' at (32, 32): the sprite is 12 tall and stands 90 above the floor (0), so its top (102) is 6 above the ceiling (96); lower z= by 6 (to 84)"
    );
    // Default radius 4, 3 from the wall along x = 0.
    let map = common::room_map("stone").replace("thing torch 32 32", "thing torch 3 32");
    scratch.write("maps/room.map", map.as_bytes());
    assert!(scratch.only_error().starts_with(
        "maps/room.map:11:1: thing 'torch' at (3, 32): its footprint (radius 4) crosses the line of the wall from vertex 'd' to vertex 'a' (line 9)"
    ));
    let map = common::room_map("stone").replace("thing torch 32 32", "thing torch 32 32 hang");
    scratch.write("maps/room.map", map.as_bytes());
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    let thing = compiled.maps()[0].things[0];
    assert_eq!((thing.radius, thing.flags), (4, THING_HANGING));
    assert_eq!(usize::from(thing.sprite), 0);
    assert_eq!(compiled.sprites()[0].width, 8);
}

#[test]
fn a_sprite_that_is_not_a_png_is_named() {
    let scratch = valid_assets("sprite_garbage", "stone");
    scratch.write("sprites/torch.png", b"GIF89a, not a PNG");
    let error = scratch.only_error();
    assert!(
        error.starts_with("sprites/torch.png:1:1: cannot decode the PNG"),
        "{error}"
    );
}

#[test]
fn a_sprite_with_no_opaque_pixel_is_refused() {
    let scratch = valid_assets("sprite_clear", "stone");
    scratch.png("sprites/torch.png", &RgbaImage::new(8, 12));
    assert_eq!(
        scratch.only_error(),
        "sprites/torch.png:1:1: every pixel is transparent (alpha below 128), so the thing would not show; paint the sprite with opaque pixels (alpha 128 or more)"
    );
    // The common sprite has opaque pixels.
    scratch.png("sprites/torch.png", &sprite());
    compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
}
