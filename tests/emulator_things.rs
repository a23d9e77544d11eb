//! Things in the ROM under the real mGBA core: on the `tiny` map the player strafes and walks
//! past the yard's things, seen through the room's portal. Every frame the ROM draws is compared
//! with the host's render of the pose it logged (identical VRAM pages), and the frames must
//! include one where a thing is drawn, one where a thing in front of the eye and on screen is
//! hidden entirely behind a wall, and one where a sprite is cut exactly at a wall's edge: a
//! pixel the sprite would cover shows the nearer wall, and its neighbour on the row shows the
//! sprite. On the bench map, the walk north across the hall (its things, the translucent lamp,
//! the grate in the passage's opening) is compared frame by frame the same way.

mod common;

use common::demos::{PlayerLine, WorldLine};
use common::rom_frames::{boot_until_playing, host_frame_matching, play_frames};
use common::*;
use portalcast::render::surface::{Surface, THING_DEPTH_MIN};
use portalcast::render::view::View;
use portalcast::render::walk::Renderer;
use portalcast_format::{MapTables, THING_HANGING, THING_TRANSLUCENT};
use portalcast_harness::Keys;

/// Rows of a sprite's edge along a wall that make a cut.
const CUT_EDGE_ROWS: usize = 6;

/// What one compared frame showed of the things.
#[derive(Default, Debug)]
struct Seen {
    /// Some thing drawn.
    drawn: bool,
    /// A thing in front of the eye whose sprite would cover pixels of the screen, none drawn.
    hidden: bool,
    /// A sprite pixel showing a nearer wall next to one showing the sprite, on one row.
    cut: bool,
}

/// Where thing `index`'s sprite would be opaque at each pixel of `view`, ignoring walls: the
/// rule of `portalcast::render::surface`, in f64.
fn sprite_covers(
    map: &MapTables,
    view: &View,
    camera: &portalcast_oracle::Camera,
    index: usize,
) -> Option<Vec<bool>> {
    let thing = &map.things[index];
    // The shipped tiny map's things are still images seen alike from every side.
    let set = &portalcast_rom::assets::SPRITE_SETS[usize::from(thing.sprite)];
    assert_eq!((set.frames, set.rotations), (1, 1), "{}", set.name);
    let sprite = &portalcast_rom::assets::SPRITES[usize::from(set.first)];
    let (sin, cos) = portalcast_oracle::engine_direction(camera);
    let (dx, dy) = (
        f64::from(thing.x_fx8) / 256.0 - camera.x,
        f64::from(thing.y_fx8) / 256.0 - camera.y,
    );
    let (x, z) = (-dx * sin + dy * cos, dx * cos + dy * sin);
    if z < f64::from(THING_DEPTH_MIN) {
        return None;
    }
    let sector = &map.sectors[usize::from(thing.sector)];
    let (width, height) = (f64::from(sprite.width), f64::from(sprite.height));
    let bottom = if thing.flags & THING_HANGING != 0 {
        f64::from(sector.ceil_z) - f64::from(thing.z) - height
    } else {
        f64::from(sector.floor_z) + f64::from(thing.z)
    };
    let viewport = &view.viewport;
    let (columns, rows) = (viewport.width as usize, viewport.height as usize);
    let mut covers = vec![false; columns * rows];
    for column in 0..columns {
        let m = (column as f64 + 0.5 - columns as f64 / 2.0) / f64::from(viewport.focal_x);
        let u = (m * z - (x - width / 2.0)).floor();
        if !(0.0..width).contains(&u) {
            continue;
        }
        for row in 0..rows {
            let k =
                (row as f64 + 0.5 - f64::from(viewport.horizon_y)) / f64::from(viewport.focal_y);
            let v = (bottom + height - (camera.eye_z - k * z)).floor();
            if (0.0..height).contains(&v) {
                covers[row * columns + column] = sprite.texel(u as usize, v as usize) != 0;
            }
        }
    }
    Some(covers)
}

/// Compares the frame of `render_line` (posed by `player`) with the host's, and says what it
/// showed of the things.
fn compare_frame(
    emulator: &portalcast_harness::Emulator,
    renderer: &mut Renderer,
    (player, world): (&PlayerLine, Option<&WorldLine>),
    render_line: &str,
) -> Seen {
    let (map, view, canvas) = host_frame_matching(emulator, renderer, (player, world), render_line);
    let columns = view.viewport.width as usize;
    let oracle_camera = portalcast_oracle::Camera::from_fixed(
        player.x,
        player.y,
        player.z,
        player.angle,
        Some(player.sector),
    );
    let mut seen = Seen::default();
    for index in 0..map.things.len() {
        let shown = |at: usize| canvas.surfaces[at] == Surface::Thing(index as u16);
        let Some(covers) = sprite_covers(&map, &view, &oracle_camera, index) else {
            continue;
        };
        let drawn = (0..covers.len()).filter(|&at| shown(at)).count();
        let covered = covers.iter().filter(|&&c| c).count();
        seen.drawn |= drawn > 0;
        seen.hidden |= drawn == 0 && covered >= 20;
        let thing_sector = map.things[index].sector;
        let nearer_wall = |at: usize| match canvas.surfaces[at] {
            Surface::Wall(w) | Surface::Upper(w) | Surface::Lower(w) => {
                let owner = map
                    .sectors
                    .iter()
                    .position(|s| (s.first_wall..s.first_wall + s.wall_count).contains(&w));
                owner != Some(usize::from(thing_sector))
            }
            _ => false,
        };
        let cut_pixels = (0..covers.len())
            .filter(|&at| {
                let column = at % columns;
                covers[at]
                    && nearer_wall(at)
                    && ((column > 0 && shown(at - 1)) || (column + 1 < columns && shown(at + 1)))
            })
            .count();
        if std::env::var_os("THINGS_DEBUG").is_some() && cut_pixels > 0 {
            let thing_columns: std::collections::BTreeSet<usize> = (0..covers.len())
                .filter(|&at| shown(at))
                .map(|at| at % columns)
                .collect();
            let cover_columns: std::collections::BTreeSet<usize> = (0..covers.len())
                .filter(|&at| covers[at])
                .map(|at| at % columns)
                .collect();
            println!("thing {index}: cut {cut_pixels} drawn {drawn} in columns {thing_columns:?}, covers columns {cover_columns:?}");
        }
        // An edge some rows long, not one pixel of rounding.
        seen.cut |= cut_pixels >= CUT_EDGE_ROWS;
    }
    seen
}

fn presses(keys: &[Keys]) -> Vec<Keys> {
    keys.iter()
        .flat_map(|&key| [key, key, key, Keys::NONE, Keys::NONE, Keys::NONE])
        .collect()
}

/// On the bench map at 240×160, a step right past the statue and north across the hall to the
/// passage: the ROM's frames, with the hall's things, the translucent lamp and the grate in the
/// passage's opening, are the host's; the first frame where the grate fills much of the view is
/// saved for the README.
#[test]
fn the_bench_hall_s_things_grate_and_translucent_lamp_match_the_host() {
    let mut emulator = boot_until_playing();
    let mut renderer = Renderer::new();
    let mut keys = presses(&[Keys::START, Keys::RIGHT, Keys::RIGHT, Keys::START]);
    keys.extend([Keys::R; 12]);
    keys.extend([Keys::UP; 400]);
    let (mut things, mut middle, mut translucent, mut saved) = (false, false, false, false);
    play_frames(&mut emulator, &keys, |emulator, player, render_line| {
        let (map, _, canvas) = host_frame_matching(emulator, &mut renderer, player, render_line);
        let count =
            |keep: &dyn Fn(Surface) -> bool| canvas.surfaces.iter().filter(|&&s| keep(s)).count();
        let middles = count(&|s| matches!(s, Surface::Middle(_)));
        things |= count(&|s| matches!(s, Surface::Thing(_))) > 0;
        middle |= middles > 0;
        translucent |= count(&|s| match s {
            Surface::Thing(t) => map.things[usize::from(t)].flags & THING_TRANSLUCENT != 0,
            _ => false,
        }) > 0;
        if middles > 2_000 && !saved && field(render_line, "res") == Some("240x160") {
            emulator
                .save_frame_png(&screenshot_dir().join("things-bench-grate.png"))
                .unwrap_or_else(|error| panic!("{error}"));
            saved = true;
        }
    });
    assert!(things, "no frame drew a thing");
    assert!(middle, "no frame drew the grate");
    assert!(translucent, "no frame drew the translucent lamp");
    assert!(saved, "the grate never filled the view at 240x160");
}

#[test]
fn things_are_drawn_hidden_and_cut_as_the_host_draws_them() {
    let mut emulator = boot_until_playing();
    let mut renderer = Renderer::new();
    let mut total = Seen::default();
    let mut compared = 0;
    // To the tiny map through the Start menu (the cursor starts on the resolution, the map is
    // two rows down; bench, grid, slopes, tiny), then strafe left along the room, walk to its east wall
    // and turn: the yard's things pass the portal's edges.
    let mut keys = presses(&[
        Keys::START,
        Keys::DOWN,
        Keys::DOWN,
        Keys::RIGHT,
        Keys::RIGHT,
        Keys::RIGHT,
        Keys::START,
    ]);
    keys.extend([Keys::L; 90]);
    keys.extend([Keys::UP; 90]);
    keys.extend([Keys::RIGHT; 60]);
    keys.extend([Keys::R; 120]);
    play_frames(&mut emulator, &keys, |emulator, player, render_line| {
        if field(render_line, "map") != Some("tiny") {
            return;
        }
        let seen = compare_frame(emulator, &mut renderer, player, render_line);
        compared += 1;
        // The first frame of each kind, for the README and for a look.
        for (kind, now, before) in [
            ("drawn", seen.drawn, total.drawn),
            ("hidden", seen.hidden, total.hidden),
            ("cut", seen.cut, total.cut),
        ] {
            if now && !before {
                emulator
                    .save_frame_png(&screenshot_dir().join(format!("things-{kind}.png")))
                    .unwrap_or_else(|error| panic!("{error}"));
            }
        }
        total.drawn |= seen.drawn;
        total.hidden |= seen.hidden;
        total.cut |= seen.cut;
    });
    println!("{compared} frames of tiny compared: {total:?}");
    assert!(
        compared > 10,
        "the ROM drew {compared} frames of the tiny map"
    );
    assert!(total.drawn, "no frame drew a thing");
    assert!(total.hidden, "no frame had a thing hidden behind a wall");
    assert!(total.cut, "no frame had a sprite cut at a wall's edge");
}
