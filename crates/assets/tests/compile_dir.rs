//! The asset directory as a whole: PNG checks, what is kept and left out, palette and colormap
//! rules, texel layouts, and writing the output.

mod common;

use common::{pattern, room_map, sprite, valid_assets, Scratch};
use image::{Rgba, RgbaImage};
use portalcast_assets::{compile_dir, CompileErrors};
use portalcast_format::{colormap_row, LIGHT_LEVELS, LIGHT_NEUTRAL, NO_TEXTURE, TRANSPARENT};

/// Asserts that compiling `scratch` fails with an error in `file` at `line:col` containing
/// `text`.
fn assert_error(scratch: &Scratch, file: &str, line: u32, col: u32, text: &str) -> CompileErrors {
    let errors = compile_dir(&scratch.dir).expect_err("the assets have an error");
    let found = errors.0.iter().any(|d| {
        d.path.ends_with(file) && d.loc.line == line && d.loc.col == col && d.message.contains(text)
    });
    assert!(
        found,
        "expected {file}:{line}:{col}: {text:?}, got:\n{errors}"
    );
    errors
}

#[test]
fn valid_directory_compiles() {
    let scratch = valid_assets("valid", "sky");
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(compiled.maps().len(), 1);
    assert!(compiled.sky().is_some());
    assert_eq!(compiled.sprites().len(), 1);
}

#[test]
fn texture_side_not_a_power_of_two() {
    let scratch = valid_assets("npot", "stone");
    scratch.png("textures/brick.png", &pattern(100, 16));
    assert_error(
        &scratch,
        "textures/brick.png",
        1,
        1,
        "width 100 is not a power of two between 8 and 256; resize it",
    );
}

#[test]
fn texture_too_small_and_too_large() {
    let scratch = valid_assets("small", "stone");
    scratch.png("textures/brick.png", &pattern(16, 4));
    assert_error(
        &scratch,
        "textures/brick.png",
        1,
        1,
        "height 4 is not a power of two between 8 and 256",
    );
    scratch.png("textures/brick.png", &pattern(512, 16));
    assert_error(
        &scratch,
        "textures/brick.png",
        1,
        1,
        "width 512 is not a power of two between 8 and 256",
    );
}

#[test]
fn texture_with_transparency_is_reported_at_the_pixel() {
    let scratch = valid_assets("alpha", "stone");
    let mut image = pattern(16, 16);
    image.put_pixel(5, 3, Rgba([0, 0, 0, 10]));
    image.put_pixel(9, 9, Rgba([0, 0, 0, 10]));
    scratch.png("textures/brick.png", &image);
    assert_error(
        &scratch,
        "textures/brick.png",
        4,
        6,
        "pixel is not opaque (alpha 10, 2 such pixels in all)",
    );
}

#[test]
fn undecodable_png() {
    let scratch = valid_assets("garbage", "stone");
    scratch.write("textures/brick.png", b"not a png at all");
    assert_error(
        &scratch,
        "textures/brick.png",
        1,
        1,
        "cannot decode the PNG",
    );
}

#[test]
fn non_square_flat_is_refused_where_the_map_uses_it() {
    // The span kernels read a flat as a side x side tile: a 32x64 floor used to compile and
    // then fail the flat kernels' assertion on the first frame (issue 16, defect 1).
    let scratch = valid_assets("flat_shape", "stone");
    scratch.png("textures/stone.png", &pattern(32, 64));
    let errors = assert_error(
        &scratch,
        "maps/room.map",
        5,
        39,
        "floor texture 'stone' is 32x64; floors and ceilings need a square texture: resize textures/stone.png to 32x32",
    );
    assert_error(
        &scratch,
        "maps/room.map",
        5,
        54,
        "ceiling texture 'stone' is 32x64",
    );
    assert_eq!(errors.0.len(), 2, "{errors}");
    // The same texture on a wall only is fine: walls take any power-of-two rectangle.
    scratch.png("textures/brick.png", &pattern(8, 64));
    scratch.png("textures/stone.png", &pattern(64, 64));
    compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    // A grid map reports it at its legend line, once for all the sectors of that kind.
    scratch.png("textures/stone.png", &pattern(64, 16));
    std::fs::remove_file(scratch.path("maps/room.map")).expect("remove map");
    scratch.write(
        "maps/cells.grid",
        b"solid # tex=brick\nopen . floor=0 ceil=64 floor_tex=stone ceil_tex=sky\nplayer @ on=.\ngrid\n#####\n#@#.#\n#...#\n#####\n",
    );
    let errors = assert_error(
        &scratch,
        "maps/cells.grid",
        2,
        34,
        "floor texture 'stone' is 64x16",
    );
    assert_eq!(errors.0.len(), 1, "{errors}");
}

#[test]
fn sky_checks() {
    let scratch = valid_assets("sky", "sky");
    scratch.png("sky/sky.png", &pattern(100, 16));
    assert_error(
        &scratch,
        "sky/sky.png",
        1,
        1,
        "width 100 is not a power of two between 64 and 1024",
    );
    scratch.png("sky/sky.png", &pattern(64, 8));
    assert_error(
        &scratch,
        "sky/sky.png",
        1,
        1,
        "height 8 is not a power of two between 16 and 256",
    );
    scratch.png("sky/sky.png", &pattern(64, 160));
    assert_error(
        &scratch,
        "sky/sky.png",
        1,
        1,
        "height 160 is not a power of two between 16 and 256",
    );
    let mut image = pattern(64, 16);
    image.put_pixel(63, 15, Rgba([1, 2, 3, 0]));
    scratch.png("sky/sky.png", &image);
    assert_error(&scratch, "sky/sky.png", 16, 64, "pixel is not opaque");
}

#[test]
fn sprite_too_large() {
    let scratch = valid_assets("sprite", "stone");
    scratch.png("sprites/torch.png", &RgbaImage::new(300, 8));
    assert_error(
        &scratch,
        "sprites/torch.png",
        1,
        1,
        "width 300 is outside 1..=256",
    );
}

#[test]
fn no_maps() {
    let scratch = valid_assets("nomaps", "stone");
    std::fs::remove_file(scratch.path("maps/room.map")).expect("remove map");
    assert_error(&scratch, "maps", 1, 1, "no maps found");
}

#[test]
fn two_maps_with_one_name() {
    let scratch = valid_assets("dupname", "stone");
    scratch.write(
        "maps/room.grid",
        b"solid # tex=brick\nopen . floor=0 ceil=64 floor_tex=stone ceil_tex=stone\nplayer @ on=.\ngrid\n###\n#@#\n###\n",
    );
    assert_error(
        &scratch,
        "maps/room.map",
        1,
        1,
        "another map is also called 'room'",
    );
}

#[test]
fn map_not_utf8() {
    let scratch = valid_assets("utf8", "stone");
    scratch.write("maps/room.map", &[0xff, 0xfe, b'v']);
    assert_error(&scratch, "maps/room.map", 1, 1, "not UTF-8");
}

#[test]
fn every_error_of_every_file_is_reported_sorted() {
    let scratch = valid_assets("many", "stone");
    scratch.write("maps/a.map", b"vertex a 0 0\nbogus\n");
    scratch.write("maps/b.map", b"player 1 1\nwall a b\n");
    scratch.png("textures/brick.png", &pattern(12, 16));
    let errors = compile_dir(&scratch.dir).expect_err("errors");
    let shown = errors.to_string();
    let lines: Vec<&str> = shown.lines().collect();
    assert!(lines.len() >= 4, "{shown}");
    assert!(
        lines
            .iter()
            .any(|l| l.contains("a.map:2:1: unknown directive 'bogus'")),
        "{shown}"
    );
    assert!(
        lines
            .iter()
            .any(|l| l.contains("b.map:2:1: wall before any sector")),
        "{shown}"
    );
    assert!(
        lines.iter().any(|l| l.contains("brick.png:1:1: width 12")),
        "{shown}"
    );
    let mut sorted = errors.0.clone();
    sorted.sort();
    assert_eq!(sorted, errors.0);
}

#[test]
fn only_what_the_maps_use_is_kept() {
    let scratch = valid_assets("used", "stone");
    scratch.png("textures/unused.png", &pattern(8, 8));
    scratch.png("sprites/barrel.png", &sprite());
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = compiled
        .textures()
        .iter()
        .map(|t| t.name.as_str())
        .collect();
    assert_eq!(names, ["brick", "stone"]);
    assert_eq!(compiled.sprites().len(), 1);
    assert!(compiled.sky().is_none(), "no sector shows the sky");
    assert_eq!(
        compiled.left_out(),
        ["textures/unused.png", "sprites/barrel.png", "sky/sky.png"]
    );
    // Brick is only on walls, stone only on flats: each keeps just the layout it needs.
    let (brick, stone) = (&compiled.textures()[0], &compiled.textures()[1]);
    assert!(!brick.columns.is_empty() && brick.rows.is_empty());
    assert!(stone.columns.is_empty() && !stone.rows.is_empty());
    // Indices were renumbered to the kept list.
    let map = compiled.map("room").expect("room map");
    assert!(map
        .walls
        .iter()
        .all(|w| w.texture == 0 && w.upper_texture == NO_TEXTURE));
    assert!(map
        .sectors
        .iter()
        .all(|s| s.floor_texture == 1 && s.ceil_texture == 1));
    assert!(!compiled
        .files_read()
        .iter()
        .any(|p| p.ends_with("unused.png")));
    assert!(compiled
        .files_read()
        .iter()
        .any(|p| p.ends_with("maps/room.map")));
    assert!(compiled
        .size_report()
        .contains("left out (no map uses them): textures/unused.png"));
}

#[test]
fn layouts_and_mip_chains() {
    let scratch = valid_assets("layout", "stone");
    // Top half red, bottom half blue: column-major runs red then blue down each column,
    // row-major has all the red rows first.
    let image = RgbaImage::from_fn(8, 8, |_, y| {
        if y < 4 {
            Rgba([255, 0, 0, 255])
        } else {
            Rgba([0, 0, 255, 255])
        }
    });
    scratch.png("textures/brick.png", &image);
    scratch.png("textures/stone.png", &image);
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    let (brick, stone) = (&compiled.textures()[0], &compiled.textures()[1]);
    assert_eq!(
        (brick.width_log2, brick.height_log2, brick.mip_count),
        (3, 3, 4)
    );
    assert_eq!(brick.columns.len(), 64 + 16 + 4 + 1);
    let (red, blue) = (brick.columns[0], brick.columns[4]);
    assert_ne!(red, blue);
    assert_eq!(
        &brick.columns[..8],
        &[red, red, red, red, blue, blue, blue, blue]
    );
    let texture = stone.texture();
    assert_eq!(texture.flat_level(0)[..32], [red; 32]);
    assert_eq!(texture.flat_level(0)[32..], [blue; 32]);
    assert_eq!(texture.chain_len(), stone.rows.len());
    assert_eq!(texture.flat_level(3).len(), 1);
    assert_eq!(
        brick.texture().wall_level(1),
        [red, red, blue, blue].repeat(4)
    );
}

#[test]
fn palette_and_colormap_rules() {
    let scratch = valid_assets("palette", "sky");
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(compiled.palette()[0], 0);
    for texture in compiled.textures() {
        assert!(!texture.columns.contains(&TRANSPARENT) && !texture.rows.contains(&TRANSPARENT));
    }
    assert!(!compiled.sky().expect("sky").texels.contains(&TRANSPARENT));
    let torch = compiled.sprites()[0].sprite();
    // Column 0 is fully transparent, column 1 has opaque rows 1..11.
    assert!((0..12).all(|v| torch.texel(0, v) == TRANSPARENT));
    assert_eq!(torch.texel(1, 0), TRANSPARENT);
    assert!((1..11).all(|v| torch.texel(1, v) != TRANSPARENT));
    assert_eq!(torch.texel(1, 11), TRANSPARENT);

    let colormap = compiled.colormap();
    let neutral = colormap_row(LIGHT_NEUTRAL);
    assert_eq!(colormap.len(), LIGHT_LEVELS);
    for (row, entries) in colormap.iter().enumerate() {
        assert_eq!(entries[0], TRANSPARENT);
        assert!(entries[1..].iter().all(|&i| i != TRANSPARENT), "row {row}");
        if row == neutral {
            assert!(entries
                .iter()
                .enumerate()
                .all(|(i, &e)| usize::from(e) == i));
        }
    }
    let brightness = |row: usize| -> u32 {
        colormap[row][1..]
            .iter()
            .map(|&i| {
                let c = compiled.palette()[usize::from(i)];
                u32::from(c & 31) + u32::from((c >> 5) & 31) + u32::from((c >> 10) & 31)
            })
            .sum()
    };
    for row in 1..LIGHT_LEVELS {
        assert!(
            brightness(row) >= brightness(row - 1),
            "row {row} is darker than row {}",
            row - 1
        );
    }
}

#[test]
fn write_to_emits_source_and_blobs() {
    let scratch = valid_assets("write", "sky");
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    let out = Scratch::new("out");
    let read = compiled.write_to(&out.dir).expect("write");
    assert!(read.iter().any(|p| p.ends_with("textures/brick.png")));
    let source = std::fs::read_to_string(out.path("assets.rs")).expect("assets.rs");
    for item in [
        "pub static PALETTE:",
        "pub static COLORMAP:",
        "pub static TEXTURES:",
        "pub static SKY:",
        "pub static SPRITES:",
        "pub static SPRITE_SETS:",
        "pub static MAPS:",
    ] {
        assert!(source.contains(item), "missing {item}");
    }
    let sky = std::fs::read(out.path("assets_sky.bin")).expect("sky blob");
    assert_eq!(sky, compiled.sky().expect("sky").texels);
    let leftovers: Vec<_> = std::fs::read_dir(&out.dir)
        .expect("out dir")
        .filter_map(|e| e.ok())
        .filter(|e| e.path().extension().is_some_and(|x| x == "tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left behind");
}

#[test]
fn a_map_with_light_effects_alone_gets_the_live_sector_table() {
    // The game keeps a live copy of the sectors of a map whose lights change, as of one whose
    // floors and ceilings move: the largest such map sizes it.
    let live_sectors = |map: &str| {
        let scratch = valid_assets("live_lights", "stone");
        scratch.write("maps/room.map", map.as_bytes());
        let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
        let out = Scratch::new("live_lights_out");
        compiled.write_to(&out.dir).expect("write");
        let source = std::fs::read_to_string(out.path("assets.rs")).expect("assets.rs");
        let lights = source
            .lines()
            .skip_while(|l| !l.starts_with("static MAP_0_LIGHTS"))
            .take_while(|l| *l != "];")
            .collect::<Vec<_>>()
            .join("\n");
        let count = source
            .lines()
            .find_map(|l| l.strip_prefix("pub const LIVE_SECTORS: usize = "))
            .expect("LIVE_SECTORS")
            .trim_end_matches(';')
            .to_string();
        (count, lights)
    };
    let glowing = room_map("stone").replace("ceil_tex=stone", "ceil_tex=stone glow=10");
    let (count, lights) = live_sectors(&glowing);
    assert_eq!(count, "1");
    assert_eq!(
        lights,
        "static MAP_0_LIGHTS: [::portalcast_format::Light; 1] = [\n    \
         ::portalcast_format::Light { sector: 0, kind: 0, low: 10, period: 120, tag: 0 },"
    );
    let (count, lights) = live_sectors(&room_map("stone"));
    assert_eq!(count, "0");
    assert_eq!(
        lights,
        "static MAP_0_LIGHTS: [::portalcast_format::Light; 0] = ["
    );
}

#[test]
fn missing_optional_folders_are_not_watched() {
    let scratch = valid_assets("nosky", "stone");
    std::fs::remove_dir_all(scratch.path("sky")).expect("remove sky folder");
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    assert!(compiled.files_read().iter().all(|p| p.exists()));
    assert!(compiled.files_read().contains(&scratch.dir));
}

// Errors that misled (issue 16, defect 5): each says what is really wrong, where.

#[test]
fn a_byte_order_mark_is_accepted() {
    let scratch = valid_assets("bom", "stone");
    let text = format!("\u{feff}{}", room_map("stone"));
    scratch.write("maps/room.map", text.as_bytes());
    compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    // Columns count from after the mark: a bad first word is at 1:1, and quoted without it.
    let text = format!("\u{feff}vortex a 0 0\n{}", room_map("stone"));
    scratch.write("maps/room.map", text.as_bytes());
    let errors = assert_error(
        &scratch,
        "maps/room.map",
        1,
        1,
        "unknown directive 'vortex'",
    );
    assert!(!errors.to_string().contains('\u{feff}'), "{errors}");
}

#[test]
fn a_bad_value_on_a_sector_line_keeps_the_sector() {
    let scratch = valid_assets("sector_value", "stone");
    let map = "vertex a 0 0\nvertex b 64 0\nvertex c 64 64\nvertex d 0 64\n\
               vertex e 128 0\nvertex f 128 64\n\
               sector west floor=0 ceil=96 floor_tex=stone ceil_tex=stone\n\
               wall a b tex=brick\nwall b c portal=east\nwall c d tex=brick\nwall d a tex=brick\n\
               sector east floor=0 ceil=96 floor_tex=stone ceil_tex=stone light=300\n\
               wall b e tex=brick\nwall e f tex=brick\nwall f c tex=brick\nwall c b portal=west\n\
               player 32 32\n";
    scratch.write("maps/room.map", map.as_bytes());
    let errors = assert_error(
        &scratch,
        "maps/room.map",
        12,
        66,
        "light 300 is out of range",
    );
    // Only the bad value: no "unknown sector 'east'" on the portal to it.
    assert_eq!(errors.0.len(), 1, "{errors}");
}

#[test]
fn a_missing_asset_directory_or_maps_folder_is_named() {
    let scratch = valid_assets("missing_dir", "stone");
    let errors = compile_dir(&scratch.path("nowhere")).expect_err("no such directory");
    assert_eq!(errors.0.len(), 1, "{errors}");
    assert!(
        errors.0[0]
            .message
            .starts_with("the asset directory does not exist"),
        "{errors}"
    );
    std::fs::remove_dir_all(scratch.path("maps")).expect("remove maps folder");
    assert_error(
        &scratch,
        "maps",
        1,
        1,
        "the asset directory has no maps folder",
    );
}

#[test]
fn an_uppercase_extension_is_a_map() {
    let scratch = valid_assets("upper", "stone");
    std::fs::rename(scratch.path("maps/room.map"), scratch.path("maps/ROOM.MAP"))
        .expect("rename map");
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    assert!(compiled.map("ROOM").is_some());
}

#[test]
fn a_map_without_sectors_says_so() {
    let scratch = valid_assets("no_sectors", "stone");
    scratch.write("maps/room.map", b"vertex a 0 0\nplayer 32 32\n");
    let errors = assert_error(&scratch, "maps/room.map", 1, 1, "the map has no sectors");
    assert_eq!(errors.0.len(), 1, "{errors}");
}

#[test]
fn a_bad_byte_is_reported_where_it_is() {
    let scratch = valid_assets("bad_byte", "stone");
    scratch.write("maps/room.map", b"vertex a 0 0\nvertex \xc3\xa9b \xff 0\n");
    // Line 2: `vertex ` is 7 characters and the two-byte e-acute one, so the 0xFF is column 11.
    assert_error(
        &scratch,
        "maps/room.map",
        2,
        11,
        "byte 0xFF is not UTF-8 text",
    );
}

#[test]
fn no_sprite_blob_is_declared_without_things() {
    // A static nothing reads makes the ROM build warn ("SPRITE_BLOB is never used").
    let scratch = valid_assets("no_things", "stone");
    let map = room_map("stone").replace("thing torch 32 32\n", "");
    scratch.write("maps/room.map", map.as_bytes());
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    let out = Scratch::new("out_no_things");
    compiled.write_to(&out.dir).expect("write");
    let source = std::fs::read_to_string(out.path("assets.rs")).expect("assets.rs");
    assert!(!source.contains("SPRITE_BLOB"), "{source}");
    assert!(source.contains("pub static SPRITES:"));
    assert!(source
        .contains("pub static SPRITE_SETS: &[::portalcast_format::SpriteSet<'static>] = &[\n];"));
}
