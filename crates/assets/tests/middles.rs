//! Portal middles and translucency (issue 17): `mid=`, `blocks` and `translucent` on a portal's
//! wall line compile to both sides' `Wall::middle` and `Wall::flags`; `translucent` on a thing
//! to `THING_TRANSLUCENT`; a set used only as a middle is compiled; and the blend table is
//! built, emitted and reported only when something is translucent, with its stated properties.

mod common;

use common::{room_map, sprite, valid_assets, Scratch};
use image::{Rgba, RgbaImage};
use portalcast_assets::{compile_dir, compile_map_str, Catalog, Compiled, CompiledMap};
use portalcast_format::{
    BlendTable, Palette, Wall, NO_TEXTURE, THING_HANGING, THING_TRANSLUCENT, WALL_MIDDLE_BLOCKS,
    WALL_MIDDLE_TRANSLUCENT,
};

/// Two rooms of one height side by side (0..128 and 128..256) joined by a portal; `west` and
/// `east` are the words added to the west room's portal line and to the east room's.
fn two_rooms(west: &str, east: &str, things: &str) -> String {
    format!(
        "vertex a 0 0\nvertex b 128 0\nvertex c 128 128\nvertex d 0 128\n\
         vertex e 256 0\nvertex f 256 128\n\
         sector west floor=0 ceil=96 floor_tex=stone ceil_tex=stone\n\
         wall a b tex=brick\nwall b c portal=east {west}\nwall c d tex=brick\nwall d a tex=brick\n\
         sector east floor=0 ceil=96 floor_tex=stone ceil_tex=stone\n\
         wall b e tex=brick\nwall e f tex=brick\nwall f c tex=brick\nwall c b portal=west {east}\n\
         player 64 64\n{things}"
    )
}

fn catalog() -> Catalog {
    Catalog::new(["brick", "stone"], ["grate", "lamp", "window"], false)
        .with_sprite_size("lamp", 15, 24)
        .with_sprite_frames("grate", 1, 1)
}

fn compile(text: &str) -> CompiledMap {
    compile_map_str("rooms.map", text, &catalog()).unwrap_or_else(|e| panic!("{e}"))
}

/// (middle, flags) of the west room's portal, then of the east room's.
fn portal_sides(map: &CompiledMap) -> [(u16, u16); 2] {
    let side = |walls: &[Wall]| {
        let wall = walls
            .iter()
            .find(|w| w.neighbour().is_some())
            .expect("a portal");
        (wall.middle, wall.flags)
    };
    let west = &map.sectors[0];
    let east = &map.sectors[1];
    let walls = |s: &portalcast_format::Sector| {
        map.walls[usize::from(s.first_wall)..][..usize::from(s.wall_count)].to_vec()
    };
    [side(&walls(west)), side(&walls(east))]
}

/// Catalog indices (sorted names): grate 0, lamp 1, window 2.
const GRATE: u16 = 0;
const WINDOW: u16 = 2;

#[test]
fn middle_words_reach_both_sides_of_the_portal() {
    let cases = [
        // Given on one side, either one: the twin gets the same.
        ("mid=grate blocks", "", [(GRATE, WALL_MIDDLE_BLOCKS); 2]),
        ("", "blocks mid=grate", [(GRATE, WALL_MIDDLE_BLOCKS); 2]),
        (
            "mid=window translucent",
            "",
            [(WINDOW, WALL_MIDDLE_TRANSLUCENT); 2],
        ),
        (
            "",
            "translucent mid=window blocks",
            [(WINDOW, WALL_MIDDLE_BLOCKS | WALL_MIDDLE_TRANSLUCENT); 2],
        ),
        ("mid=grate", "", [(GRATE, 0); 2]),
        // The same on both sides.
        (
            "mid=grate blocks",
            "blocks mid=grate",
            [(GRATE, WALL_MIDDLE_BLOCKS); 2],
        ),
        // None.
        ("upper=brick", "", [(NO_TEXTURE, 0); 2]),
    ];
    for (west, east, expected) in cases {
        let map = compile(&two_rooms(west, east, ""));
        assert_eq!(portal_sides(&map), expected, "west {west:?}, east {east:?}");
        for wall in map.walls.iter().filter(|w| w.neighbour().is_none()) {
            assert_eq!((wall.middle, wall.flags), (NO_TEXTURE, 0), "solid walls");
        }
    }
}

#[test]
fn sides_that_disagree_are_refused_once_at_the_later_line() {
    for (west, east) in [
        ("mid=grate", "mid=window"),
        ("mid=grate blocks", "mid=grate"),
        ("mid=window", "mid=window translucent"),
    ] {
        let errors = compile_map_str("rooms.map", &two_rooms(west, east, ""), &catalog())
            .expect_err("the sides disagree");
        assert_eq!(errors.0.len(), 1, "{errors}");
        let error = &errors.0[0];
        assert_eq!(error.loc.line, 16, "{error}");
        assert!(
            error.message.contains("(line 9)")
                && error.message.contains("one image seen from both sides"),
            "{error}"
        );
    }
}

#[test]
fn translucent_things_in_both_formats() {
    let map = compile(&two_rooms(
        "",
        "",
        "thing lamp 64 32 hang translucent\nthing lamp 200 64 translucent\nthing lamp 32 96\n",
    ));
    let flags: Vec<u16> = map.things.iter().map(|t| t.flags).collect();
    assert_eq!(
        flags,
        [THING_HANGING | THING_TRANSLUCENT, 0, THING_TRANSLUCENT]
    );
    let grid = "cell 64\nsolid # tex=brick\n\
                open . floor=0 ceil=128 floor_tex=stone ceil_tex=stone\n\
                player @ on=. angle=0\n\
                thing l lamp on=. translucent hang\n\
                grid\n#####\n#@.l#\n#####\n";
    let map = compile_map_str("rooms.grid", grid, &catalog()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.things[0].flags, THING_HANGING | THING_TRANSLUCENT);
}

/// A scratch asset directory: the one-room map's images, plus a grate (used only as a middle,
/// if the map says so) and `map` as `maps/room.map`.
fn assets_with(label: &str, map: &str) -> Scratch {
    let scratch = valid_assets(label, "stone");
    scratch.png(
        "sprites/grate.png",
        &RgbaImage::from_fn(8, 16, |x, _| {
            if x % 4 == 0 {
                Rgba([90, 90, 100, 255])
            } else {
                Rgba([0, 0, 0, 0])
            }
        }),
    );
    scratch.write("maps/room.map", map.as_bytes());
    scratch
}

fn compile_assets(scratch: &Scratch) -> Compiled {
    compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_set_used_only_as_a_middle_is_compiled_and_indexed() {
    let scratch = assets_with(
        "middle_only",
        &two_rooms("mid=grate blocks", "", "thing torch 32 32\n"),
    );
    let compiled = compile_assets(&scratch);
    let names: Vec<&str> = compiled
        .sprite_sets()
        .iter()
        .map(|s| s.name.as_str())
        .collect();
    assert_eq!(names, ["grate", "torch"]);
    assert_eq!(compiled.left_out(), ["sky/sky.png"]);
    let map = &compiled.maps()[0];
    assert_eq!(portal_sides(map), [(0, WALL_MIDDLE_BLOCKS); 2]);
    assert_eq!(map.things[0].sprite, 1, "the torch after the grate");
    // Nothing translucent: no blend table.
    assert!(compiled.blend().is_none());

    // Unused, the grate is left out unread.
    let scratch = assets_with("middle_unused", &two_rooms("", "", "thing torch 32 32\n"));
    let compiled = compile_assets(&scratch);
    assert_eq!(compiled.left_out(), ["sprites/grate.png", "sky/sky.png"]);
}

#[test]
fn an_animated_or_rotated_set_is_no_middle() {
    let scratch = assets_with("middle_animated", &two_rooms("mid=flame", "", ""));
    for frame in 1..=2 {
        scratch.png(&format!("sprites/flame.{frame}.png"), &sprite());
    }
    let errors = compile_dir(&scratch.dir).expect_err("an animated middle");
    let shown = errors.to_string();
    assert!(
        shown.contains("room.map:9:26: mid= needs a still image, but sprite set 'flame' has 2 animation frames"),
        "{shown}"
    );
}

/// What the GBA shows for each palette entry, 8 bits a channel.
fn shown(palette: &Palette) -> Vec<[i32; 3]> {
    let expand = |five: u16| {
        let five = (five & 0x1f) as i32;
        (five << 3) | (five >> 2)
    };
    palette
        .iter()
        .map(|&c| [expand(c), expand(c >> 5), expand(c >> 10)])
        .collect()
}

fn check_blend_properties(blend: &BlendTable, palette: &Palette) {
    let shown = shown(palette);
    let distance = |a: [i32; 3], b: [i32; 3]| (0..3).map(|k| (a[k] - b[k]).pow(2)).sum::<i32>();
    for behind in 0..256 {
        for front in 0..256 {
            let entry = blend[behind][front];
            if behind == 0 && front == 0 {
                assert_eq!(entry, 0, "transparent on transparent");
                continue;
            }
            assert_ne!(entry, 0, "blend[{behind}][{front}] is opaque");
            assert_eq!(entry, blend[front][behind], "symmetric");
            if behind == front {
                assert_eq!(usize::from(entry), behind, "a colour blended with itself");
                continue;
            }
            let average = [0, 1, 2].map(|k| (shown[behind][k] + shown[front][k] + 1) / 2);
            let best = (1..256).map(|i| distance(shown[i], average)).min();
            assert_eq!(
                Some(distance(shown[usize::from(entry)], average)),
                best,
                "blend[{behind}][{front}] is a nearest colour to the average"
            );
        }
    }
}

#[test]
fn the_blend_table_is_built_emitted_and_reported_only_when_used() {
    // A translucent middle.
    let scratch = assets_with(
        "blend_middle",
        &two_rooms("mid=grate translucent", "", "thing torch 32 32\n"),
    );
    let with_middle = compile_assets(&scratch);
    assert_eq!(
        portal_sides(&with_middle.maps()[0]),
        [(0, WALL_MIDDLE_TRANSLUCENT); 2]
    );
    let blend = with_middle
        .blend()
        .expect("a translucent middle needs the table");
    check_blend_properties(blend, with_middle.palette());

    // A translucent thing.
    let scratch = assets_with(
        "blend_thing",
        &room_map("stone").replace("thing torch 32 32", "thing torch 32 32 translucent"),
    );
    let with_thing = compile_assets(&scratch);
    assert!(with_thing.blend().is_some());
    assert_eq!(with_thing.maps()[0].things[0].flags, THING_TRANSLUCENT);
    let out = Scratch::new("blend_out");
    with_thing.write_to(&out.dir).expect("write");
    let blob = std::fs::read(out.path("assets_blend.bin")).expect("the blend blob");
    assert_eq!(blob, with_thing.blend().expect("table").as_flattened());
    let source = std::fs::read_to_string(out.path("assets.rs")).expect("assets.rs");
    assert!(source.contains(
        "static BLEND_BLOB: ::portalcast_format::Align4<[u8; 65536]> = ::portalcast_format::Align4(*include_bytes!("
    ));
    assert!(source.contains(
        "pub static BLEND: Option<&'static ::portalcast_format::BlendTable> = Some(BLEND_TABLE);"
    ));
    let report = with_thing.size_report();
    assert!(
        report.contains("blend           65540  256 x 256 50 % blend table"),
        "{report}"
    );

    // Nothing translucent.
    let scratch = assets_with("blend_none", &room_map("stone"));
    let without = compile_assets(&scratch);
    assert!(without.blend().is_none());
    let out = Scratch::new("blend_none_out");
    without.write_to(&out.dir).expect("write");
    assert_eq!(
        std::fs::read(out.path("assets_blend.bin")).expect("written, empty"),
        Vec::<u8>::new()
    );
    let source = std::fs::read_to_string(out.path("assets.rs")).expect("assets.rs");
    assert!(!source.contains("BLEND_BLOB"), "nothing unused is declared");
    assert!(source
        .contains("pub static BLEND: Option<&'static ::portalcast_format::BlendTable> = None;"));
    assert!(without
        .size_report()
        .contains("blend               0  none (nothing translucent)"));
}

#[test]
fn walls_are_emitted_with_their_middle_and_flags() {
    let scratch = assets_with(
        "emit_middle",
        &two_rooms("mid=grate blocks", "", "thing torch 32 32\n"),
    );
    let compiled = compile_assets(&scratch);
    let out = Scratch::new("emit_middle_out");
    compiled.write_to(&out.dir).expect("write");
    let source = std::fs::read_to_string(out.path("assets.rs")).expect("assets.rs");
    let portal_lines: Vec<&str> = source
        .lines()
        .filter(|l| l.contains("::portalcast_format::Wall {") && !l.contains("portal: 65535"))
        .collect();
    assert_eq!(portal_lines.len(), 2, "{source}");
    for line in portal_lines {
        assert!(line.ends_with("middle: 0, flags: 1 },"), "{line}");
    }
    assert!(source
        .lines()
        .filter(|l| l.contains("portal: 65535"))
        .all(|l| l.ends_with("middle: 65535, flags: 0 },")));
}
