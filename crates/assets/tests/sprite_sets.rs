//! Sprite sets (`docs/MAP_FORMAT.md`, "Sprites"): a still image, animation frames as numbered
//! PNGs or a strip, eight rotations, frames with rotations. Each compiles to the right
//! `SpriteSet` and images in the right order; each naming or image error is reported at the
//! file; `anim=` sets a thing's frame ticks.

mod common;

use common::{room_map, sprite, valid_assets, Scratch};
use image::{Rgba, RgbaImage};
use portalcast_assets::{compile_dir, compile_map_str, Catalog, Compiled, CompiledSprite};
use portalcast_format::{SpriteSet, TRANSPARENT};

/// A 6×10 sprite, transparent but for a 1-texel-wide opaque column at `column` (0..6) of colour
/// `rgb`: images told apart by where their column stands.
fn marked(column: u32, rgb: [u8; 3]) -> RgbaImage {
    RgbaImage::from_fn(6, 10, |x, _| {
        if x == column {
            Rgba([rgb[0], rgb[1], rgb[2], 255])
        } else {
            Rgba([0, 0, 0, 0])
        }
    })
}

/// Eight distinct colours.
const COLOURS: [[u8; 3]; 8] = [
    [230, 40, 40],
    [40, 230, 40],
    [40, 40, 230],
    [230, 230, 40],
    [40, 230, 230],
    [230, 40, 230],
    [250, 250, 250],
    [120, 60, 20],
];

/// The valid one-room assets, with the thing `thing` (a `thing` line's words after the keyword,
/// e.g. `flame 32 32`) instead of the torch.
fn assets_with(label: &str, thing: &str) -> Scratch {
    let scratch = valid_assets(label, "stone");
    let map = room_map("stone").replace("thing torch 32 32", &format!("thing {thing}"));
    scratch.write("maps/room.map", map.as_bytes());
    scratch
}

fn compile(scratch: &Scratch) -> Compiled {
    compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"))
}

/// The set called `name` and its images.
fn set<'c>(compiled: &'c Compiled, name: &str) -> (SpriteSet<'c>, &'c [CompiledSprite]) {
    let set = compiled
        .sprite_sets()
        .iter()
        .find(|s| s.name == name)
        .unwrap_or_else(|| panic!("no set {name}"))
        .set();
    let first = usize::from(set.first);
    let count = usize::from(set.frames) * usize::from(set.rotations);
    (set, &compiled.sprites()[first..first + count])
}

/// The opaque columns of an image.
fn opaque_columns(image: &CompiledSprite) -> Vec<usize> {
    let sprite = image.sprite();
    (0..usize::from(sprite.width))
        .filter(|&u| (0..usize::from(sprite.height)).any(|v| sprite.texel(u, v) != TRANSPARENT))
        .collect()
}

/// The palette colour (8-bit RGB, rounded from BGR555) of an image's texel.
fn colour(compiled: &Compiled, image: &CompiledSprite, u: usize, v: usize) -> [i32; 3] {
    let bgr = compiled.palette()[usize::from(image.sprite().texel(u, v))];
    [bgr & 31, (bgr >> 5) & 31, (bgr >> 10) & 31].map(|c| i32::from(c) * 255 / 31)
}

/// Which of [`COLOURS`] a palette colour is nearest.
fn nearest(rgb: [i32; 3]) -> usize {
    (0..COLOURS.len())
        .min_by_key(|&k| {
            rgb.iter()
                .zip(COLOURS[k])
                .map(|(&a, b)| (a - i32::from(b)).pow(2))
                .sum::<i32>()
        })
        .unwrap_or(0)
}

#[test]
fn a_still_image_is_a_set_of_one() {
    let compiled = compile(&valid_assets("still", "stone"));
    let (torch, images) = set(&compiled, "torch");
    assert_eq!(
        torch,
        SpriteSet {
            name: "torch",
            first: 0,
            frames: 1,
            rotations: 1
        }
    );
    assert_eq!(images[0].name, "torch");
    assert_eq!(compiled.maps()[0].things[0].sprite, 0);
}

#[test]
fn numbered_frames_are_one_set_in_numeric_order() {
    // Twelve frames: flame.10.png sorts before flame.2.png by name, not by number.
    let scratch = assets_with("frames", "flame 32 32");
    for k in 1..=12u32 {
        scratch.png(
            &format!("sprites/flame.{k}.png"),
            &marked((k - 1) % 6, COLOURS[(k as usize - 1) % 8]),
        );
    }
    let compiled = compile(&scratch);
    let (flame, images) = set(&compiled, "flame");
    assert_eq!((flame.frames, flame.rotations), (12, 1));
    let names: Vec<&str> = images.iter().map(|i| i.name.as_str()).collect();
    let expected: Vec<String> = (1..=12).map(|k| format!("flame.{k}")).collect();
    assert_eq!(names, expected);
    for (k, image) in images.iter().enumerate() {
        assert_eq!(opaque_columns(image), [k % 6], "{}", image.name);
        assert_eq!(nearest(colour(&compiled, image, k % 6, 0)), k % 8);
    }
    // The sets are sorted by name and their images follow each other: flame, then torch.
    let sets: Vec<(&str, u16)> = compiled
        .sprite_sets()
        .iter()
        .map(|s| (s.name.as_str(), s.first))
        .collect();
    assert_eq!(sets, [("flame", 0)]);
    assert!(
        compiled
            .left_out()
            .contains(&"sprites/torch.png".to_string()),
        "the torch is no longer placed"
    );
}

#[test]
fn a_strip_is_cut_into_its_frames() {
    // Four 6×10 frames side by side: frame k has its column at k and colour k.
    let strip = RgbaImage::from_fn(24, 10, |x, _| {
        let (k, column) = (x / 6, x % 6);
        if column == k {
            let c = COLOURS[k as usize];
            Rgba([c[0], c[1], c[2], 255])
        } else {
            Rgba([0, 0, 0, 0])
        }
    });
    let scratch = assets_with("strip", "flame 32 32 anim=3");
    scratch.png("sprites/flame.strip4.png", &strip);
    let compiled = compile(&scratch);
    let (flame, images) = set(&compiled, "flame");
    assert_eq!((flame.frames, flame.rotations), (4, 1));
    for (k, image) in images.iter().enumerate() {
        assert_eq!(image.name, format!("flame.{}", k + 1));
        assert_eq!((image.width, image.height), (6, 10));
        assert_eq!(opaque_columns(image), [k]);
        assert_eq!(nearest(colour(&compiled, image, k, 9)), k);
    }
    assert_eq!(compiled.maps()[0].things[0].frame_ticks, 3);
    // The same frames as separate files compile to the same images.
    let separate = assets_with("strip_as_files", "flame 32 32");
    for k in 0..4u32 {
        separate.png(
            &format!("sprites/flame.{}.png", k + 1),
            &marked(k, COLOURS[k as usize]),
        );
    }
    let separate = compile(&separate);
    let (_, separate_images) = set(&separate, "flame");
    assert_eq!(separate_images, images);
}

#[test]
fn eight_rotations_are_one_set_in_rotation_order() {
    let scratch = assets_with("rotations", "statue 32 32 angle=45");
    for r in 0..8u32 {
        scratch.png(
            &format!("sprites/statue.r{r}.png"),
            &marked(r % 6, COLOURS[r as usize]),
        );
    }
    let compiled = compile(&scratch);
    let (statue, images) = set(&compiled, "statue");
    assert_eq!((statue.first, statue.frames, statue.rotations), (0, 1, 8));
    for (r, image) in images.iter().enumerate() {
        assert_eq!(image.name, format!("statue.r{r}"));
        assert_eq!(opaque_columns(image), [r % 6]);
        assert_eq!(nearest(colour(&compiled, image, r % 6, 5)), r);
    }
    assert_eq!(statue.image(1000, 8, 5), 5);
}

#[test]
fn frames_with_rotations_are_frames_major() {
    let scratch = assets_with("frames_rotations", "knight 32 32");
    for k in 1..=3u32 {
        for r in 0..8u32 {
            scratch.png(
                &format!("sprites/knight.{k}.r{r}.png"),
                &marked(k - 1, COLOURS[r as usize]),
            );
        }
    }
    let compiled = compile(&scratch);
    let (knight, images) = set(&compiled, "knight");
    assert_eq!((knight.frames, knight.rotations), (3, 8));
    for (index, image) in images.iter().enumerate() {
        let (k, r) = (index / 8, index % 8);
        assert_eq!(image.name, format!("knight.{}.r{r}", k + 1));
        assert_eq!(opaque_columns(image), [k]);
        assert_eq!(nearest(colour(&compiled, image, k, 0)), r);
    }
    // SpriteSet::image finds the third frame (ticks 16..24 at 8 a frame), rotation 3.
    assert_eq!(
        knight.image(17, 8, 3),
        usize::from(knight.first) + 2 * 8 + 3
    );
}

#[test]
fn the_emitted_tables_index_sets_and_carry_frame_ticks() {
    let scratch = assets_with("emit_sets", "flame 32 32 anim=12");
    scratch.write(
        "maps/room.map",
        room_map("stone")
            .replace(
                "thing torch 32 32",
                "thing flame 32 32 anim=12\nthing torch 96 96",
            )
            .as_bytes(),
    );
    scratch.png(
        "sprites/flame.strip2.png",
        &RgbaImage::from_pixel(8, 10, Rgba([200, 90, 20, 255])),
    );
    let compiled = compile(&scratch);
    let out = Scratch::new("emit_sets_out");
    compiled.write_to(&out.dir).expect("write");
    let source = std::fs::read_to_string(out.path("assets.rs")).expect("assets.rs");
    assert!(source.contains(
        "pub static SPRITE_SETS: &[::portalcast_format::SpriteSet<'static>] = &[\n    \
         ::portalcast_format::SpriteSet { name: \"flame\", first: 0, frames: 2, rotations: 1 },\n    \
         ::portalcast_format::SpriteSet { name: \"torch\", first: 2, frames: 1, rotations: 1 },\n];"
    ), "{source}");
    assert!(
        source.contains("name: \"flame.2\", width: 4, height: 10"),
        "{source}"
    );
    assert!(
        source.contains("sprite: 0, sector: 0, z: 0, radius: 2, flags: 0, frame_ticks: 12 }"),
        "{source}"
    );
    assert!(
        source.contains("sprite: 1, sector: 0, z: 0, radius: 4, flags: 0, frame_ticks: 8 }"),
        "{source}"
    );
    assert!(compiled.size_report().contains("3 images of 2 sprite sets"));
}

#[test]
fn unused_sets_are_left_out_unread() {
    let scratch = valid_assets("unused_sets", "stone");
    // Not even decoded: garbage in an unused set is no error.
    for r in 0..8 {
        scratch.write(&format!("sprites/statue.r{r}.png"), b"not a PNG");
    }
    scratch.png("sprites/flame.strip3.png", &RgbaImage::new(7, 5));
    let compiled = compile(&scratch);
    let mut left_out = vec!["sprites/flame.strip3.png".to_string()];
    left_out.extend((0..8).map(|r| format!("sprites/statue.r{r}.png")));
    left_out.push("sky/sky.png".to_string());
    assert_eq!(compiled.left_out(), left_out);
    assert_eq!(compiled.sprite_sets().len(), 1);
}

#[test]
fn the_catalog_knows_set_names() {
    let catalog = Catalog::new(["brick", "stone"], ["flame", "statue"], false);
    assert_eq!(catalog.sprite_sets(), ["flame", "statue"]);
    let map = compile_map_str(
        "room.map",
        &room_map("stone").replace("thing torch 32 32", "thing statue 32 32"),
        &catalog,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.things[0].sprite, 1);
}

// File-name errors: reported whether or not a map uses the set.

#[test]
fn a_file_name_that_follows_no_scheme_is_refused() {
    let scratch = valid_assets("no_scheme", "stone");
    scratch.png("sprites/flame.x.png", &sprite());
    // Hidden files are ignored.
    scratch.png("sprites/._torch.png", &sprite());
    let error = scratch.only_error();
    assert!(
        error.starts_with(
            "sprites/flame.x.png:1:1: the file name follows none of the sprite file schemes; name a sprite set's images NAME.png (still), NAME.1.png, NAME.2.png, ..."
        ),
        "{error}"
    );
}

#[test]
fn mixed_schemes_are_refused() {
    let scratch = valid_assets("mixed", "stone");
    scratch.png("sprites/torch.1.png", &sprite());
    scratch.png("sprites/torch.2.png", &sprite());
    assert_eq!(
        scratch.errors(),
        [1, 2].map(|k| format!(
            "sprites/torch.{k}.png:1:1: sprite set 'torch' mixes file schemes: this file is an animation frame (NAME.K.png) but sprites/torch.png is a still image (NAME.png); give a set one scheme: remove or rename the files of the other"
        ))
    );
}

#[test]
fn a_gap_in_the_frame_numbers_is_refused() {
    let scratch = valid_assets("gap", "stone");
    for k in [1, 2, 4, 6] {
        scratch.png(&format!("sprites/flame.{k}.png"), &sprite());
    }
    assert_eq!(
        scratch.only_error(),
        "sprites/flame.4.png:1:1: sprite set 'flame' has no frames 3, 5 (sprites/flame.3.png, sprites/flame.5.png); number the frames from 1 without gaps: add the missing frames or renumber this one and those after it"
    );
}

#[test]
fn frames_from_zero_or_with_leading_zeros_are_refused() {
    let scratch = valid_assets("frame_zero", "stone");
    scratch.png("sprites/flame.0.png", &sprite());
    scratch.png("sprites/flame.01.png", &sprite());
    assert_eq!(
        scratch.errors(),
        [
            "sprites/flame.0.png:1:1: frame 0: animation frames are numbered from 1; renumber the frames of 'flame' from 1",
            "sprites/flame.01.png:1:1: frame number '01' has a leading zero; write it flame.1.png",
        ]
    );
}

#[test]
fn a_single_numbered_frame_is_refused() {
    let scratch = valid_assets("one_frame", "stone");
    scratch.png("sprites/flame.1.png", &sprite());
    assert_eq!(
        scratch.only_error(),
        "sprites/flame.1.png:1:1: sprite set 'flame' has only frame 1; an animation needs 2 frames or more: add sprites/flame.2.png, or rename this file flame.png for a still set"
    );
}

#[test]
fn a_strip_of_fewer_than_two_frames_is_refused() {
    let scratch = valid_assets("strip1", "stone");
    scratch.png("sprites/flame.strip1.png", &sprite());
    assert_eq!(
        scratch.only_error(),
        "sprites/flame.strip1.png:1:1: a strip holds at least 2 frames side by side (flame.stripK.png, K 2 or more); name a single image flame.png"
    );
}

#[test]
fn two_strips_for_one_set_are_refused() {
    let scratch = valid_assets("two_strips", "stone");
    scratch.png("sprites/flame.strip2.png", &RgbaImage::new(8, 4));
    scratch.png("sprites/flame.strip4.png", &RgbaImage::new(8, 4));
    assert_eq!(
        scratch.only_error(),
        "sprites/flame.strip4.png:1:1: sprite set 'flame' already has the strip sprites/flame.strip2.png; give a set one strip: remove one of them"
    );
}

#[test]
fn missing_rotations_are_refused() {
    let scratch = valid_assets("rotations_missing", "stone");
    for r in [0, 1, 2, 4, 5, 7] {
        scratch.png(&format!("sprites/statue.r{r}.png"), &sprite());
    }
    assert_eq!(
        scratch.only_error(),
        "sprites/statue.r0.png:1:1: sprite set 'statue' has no rotation r3, r6 (sprites/statue.r3.png, sprites/statue.r6.png); a set with rotations needs all eight, r0 to r7: add the missing ones, or keep a single image for a set that looks the same from every side"
    );
    // A rotation beyond r7.
    scratch.png("sprites/statue.r8.png", &sprite());
    assert!(scratch.errors().contains(
        &"sprites/statue.r8.png:1:1: rotation r8 does not exist; the eight rotations are r0 to r7 (docs/MAP_FORMAT.md, \"Sprites\")".to_string()
    ));
}

#[test]
fn each_frame_needs_all_its_rotations() {
    let scratch = valid_assets("frame_rotations_missing", "stone");
    for (k, r) in (1..=2).flat_map(|k| (0..8).map(move |r| (k, r))) {
        if (k, r) != (2, 6) {
            scratch.png(&format!("sprites/knight.{k}.r{r}.png"), &sprite());
        }
    }
    assert_eq!(
        scratch.only_error(),
        "sprites/knight.2.r0.png:1:1: frame 2 of sprite set 'knight' has no rotation r6 (sprites/knight.2.r6.png); a set with rotations needs all eight, r0 to r7: add the missing ones, or keep a single image for a set that looks the same from every side"
    );
    // One frame only: it should be a set of rotations.
    let scratch = valid_assets("frame_rotations_one", "stone");
    for r in 0..8 {
        scratch.png(&format!("sprites/knight.1.r{r}.png"), &sprite());
    }
    assert_eq!(
        scratch.only_error(),
        "sprites/knight.1.r0.png:1:1: sprite set 'knight' has only frame 1; an animation needs 2 frames or more: add sprites/knight.2.r0.png ... knight.2.r7.png, or rename its rotations knight.r0.png ... knight.r7.png for a still set"
    );
}

// Image errors: reported for the sets the maps use, whose images are read.

#[test]
fn a_strip_whose_width_does_not_divide_is_refused() {
    let scratch = assets_with("strip_width", "flame 32 32");
    scratch.png(
        "sprites/flame.strip4.png",
        &RgbaImage::from_pixel(30, 10, Rgba([200, 90, 20, 255])),
    );
    assert_eq!(
        scratch.only_error(),
        "sprites/flame.strip4.png:1:1: the strip is 30 wide, which does not divide into its 4 frames (the name says 4); make it 28 wide (4 frames of 7) or give the right count in the name"
    );
}

#[test]
fn a_fully_transparent_strip_frame_is_refused_where_it_starts() {
    let scratch = assets_with("strip_clear", "flame 32 32");
    let strip = RgbaImage::from_fn(18, 10, |x, _| {
        if (6..12).contains(&x) {
            Rgba([0, 0, 0, 0])
        } else {
            Rgba([200, 90, 20, 255])
        }
    });
    scratch.png("sprites/flame.strip3.png", &strip);
    assert_eq!(
        scratch.only_error(),
        "sprites/flame.strip3.png:1:7: frame 2 of the strip (columns 6 to 11) is fully transparent (alpha below 128), so the thing would vanish on that frame; paint it with opaque pixels (alpha 128 or more)"
    );
}

#[test]
fn images_of_one_set_must_share_their_size() {
    let scratch = assets_with("sizes", "flame 32 32");
    scratch.png("sprites/flame.1.png", &marked(0, COLOURS[0]));
    scratch.png("sprites/flame.2.png", &marked(1, COLOURS[1]));
    scratch.png("sprites/flame.3.png", &sprite());
    assert_eq!(
        scratch.only_error(),
        "sprites/flame.3.png:1:1: the image is 8x12 but sprites/flame.1.png is 6x10; all images of sprite set 'flame' must be the same size: resize this one"
    );
}

#[test]
fn each_image_of_a_set_is_checked() {
    let scratch = assets_with("rotation_clear", "statue 32 32");
    for r in 0..8 {
        let image = if r == 5 {
            RgbaImage::new(6, 10)
        } else {
            marked(0, COLOURS[0])
        };
        scratch.png(&format!("sprites/statue.r{r}.png"), &image);
    }
    assert!(scratch
        .only_error()
        .starts_with("sprites/statue.r5.png:1:1: every pixel is transparent (alpha below 128)"));
}

#[test]
fn things_check_their_footprint_against_the_set_size() {
    // Frames 6 wide: radius 3 at least.
    let scratch = assets_with("set_radius", "flame 32 32 radius=2");
    scratch.png("sprites/flame.1.png", &marked(0, COLOURS[0]));
    scratch.png("sprites/flame.2.png", &marked(1, COLOURS[1]));
    assert!(scratch.only_error().starts_with(
        "maps/room.map:11:26: radius=2 is less than half the width of the sprite (6); use radius=3"
    ));
}

// `anim=`.

#[test]
fn anim_sets_the_frame_ticks_in_text_and_grid_maps() {
    let catalog = Catalog::new(["brick", "stone"], ["flame", "torch"], false);
    let text = room_map("stone").replace(
        "thing torch 32 32",
        "thing flame 32 32 anim=1\nthing torch 96 96\nthing flame 64 96 anim=255 solid",
    );
    let map = compile_map_str("room.map", &text, &catalog).unwrap_or_else(|e| panic!("{e}"));
    // The solid flame first (a sector's solid things lead its list), then the others in order.
    let ticks: Vec<u16> = map.things.iter().map(|t| t.frame_ticks).collect();
    assert_eq!(ticks, [255, 1, 8]);
    let grid = "cell 64\nsolid # tex=brick\n\
                open . floor=0 ceil=128 floor_tex=stone ceil_tex=stone\n\
                player @ on=.\nthing f flame anim=5 on=.\nthing t torch on=.\n\
                grid\n#####\n#@.f#\n#t..#\n#####\n";
    let map = compile_map_str("room.grid", grid, &catalog).unwrap_or_else(|e| panic!("{e}"));
    let ticks: Vec<u16> = map.things.iter().map(|t| t.frame_ticks).collect();
    assert_eq!(ticks, [5, 8]);
}

#[test]
fn bad_anim_values_are_located() {
    let catalog = Catalog::new(["brick", "stone"], ["flame"], false);
    for (words, col, message) in [
        ("anim=0", 24, "anim 0 is out of range; use 1..=255"),
        ("anim=256", 24, "anim 256 is out of range; use 1..=255"),
        (
            "anim=fast",
            24,
            "anim 'fast' is not an integer; write digits with an optional '-'",
        ),
        ("anim=4 anim=5", 26, "'anim' is set twice; keep one"),
    ] {
        let text =
            room_map("stone").replace("thing torch 32 32", &format!("thing flame 32 32 {words}"));
        let errors = compile_map_str("room.map", &text, &catalog).expect_err(words);
        assert_eq!(
            errors.to_string(),
            format!("room.map:11:{col}: {message}"),
            "{words}"
        );
    }
}
