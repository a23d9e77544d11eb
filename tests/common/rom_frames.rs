//! The ROM's frames against the host's: play keys a frame at a time, and render each frame the
//! ROM drew from its logged pose and live world on the host, requiring identical VRAM pages.

use super::demos::{render_line_settings, PlayerLine, WorldLine, WorldLines};
use super::*;
use portalcast::frame::PAGE_ROW_HALFWORDS;
use portalcast::render::view::View;
use portalcast::render::walk::Renderer;
use portalcast_format::MapTables;
use portalcast_harness::Keys;
use portalcast_oracle::RecordingCanvas;

/// The host's render of the ROM's frame of `render_line` (posed by `player`, its live world as
/// `world` gives it), recording each pixel's surface; panics unless the ROM's VRAM page is
/// identical.
pub fn host_frame_matching(
    emulator: &portalcast_harness::Emulator,
    renderer: &mut Renderer,
    (player, world): (&PlayerLine, Option<&WorldLine>),
    render_line: &str,
) -> (MapTables<'static>, View, RecordingCanvas) {
    let (map, settings) = render_line_settings(render_line);
    let camera = player.camera();
    let view = View::new(&camera, &settings).at_tick(player.tick);
    let mut canvas = RecordingCanvas::new(settings.resolution);
    let live = WorldLine::world_of(world, &map);
    renderer.render(
        &live.map(&map),
        &portalcast_rom::demo::render_assets(),
        &view,
        &mut canvas,
    );
    let vram = read_page(emulator, number(render_line, "page") as u32);
    let halfwords = settings.resolution.height() * PAGE_ROW_HALFWORDS;
    let differing = vram.halfwords[..halfwords]
        .iter()
        .zip(&canvas.page.halfwords[..halfwords])
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "{render_line}: halfwords differ from the host"
    );
    (map, view, canvas)
}

/// The ROM booted with its per-frame lines on, run until the game draws its first frame (keys
/// before it are not seen).
pub fn boot_until_playing() -> portalcast_harness::Emulator {
    boot_rom_until_playing(&portalcast_xtask::rom_for_tests())
}

/// [`boot_until_playing`] with the ROM at `rom`.
pub fn boot_rom_until_playing(rom: &std::path::Path) -> portalcast_harness::Emulator {
    let mut emulator =
        portalcast_harness::Emulator::load(rom).unwrap_or_else(|error| panic!("{error}"));
    for _ in FRAME_LINES_HOLD {
        emulator.set_keys(FRAME_LINES_KEY);
        emulator
            .run_frame()
            .unwrap_or_else(|error| panic!("{error}"));
    }
    emulator.set_keys(Keys::NONE);
    let started = (0..120).any(|_| {
        emulator
            .run_frame()
            .unwrap_or_else(|error| panic!("{error}"));
        emulator
            .drain_log()
            .iter()
            .any(|line| line.is_debug_print() && line.text.starts_with("render "))
    });
    assert!(started, "the ROM drew no frame");
    emulator
}

/// Key presses through the Start menu: each held 3 frames, then 3 frames of nothing.
/// Plays `keys` a frame each and calls `frame` with every frame the ROM draws outside the Start
/// menu: the emulator, the pose its `player` line logged with the live world its `world` line
/// logged, and its `render` line.
pub fn play_frames(
    emulator: &mut portalcast_harness::Emulator,
    keys: &[Keys],
    mut frame: impl FnMut(&portalcast_harness::Emulator, (&PlayerLine, Option<&WorldLine>), &str),
) {
    let mut player = None;
    let mut world = None;
    let mut world_lines = WorldLines::default();
    for &held in keys {
        emulator.set_keys(held);
        emulator
            .run_frame()
            .unwrap_or_else(|error| panic!("{error}"));
        for line in emulator.drain_log() {
            if !line.is_debug_print() {
                continue;
            }
            if std::env::var_os("THINGS_DEBUG").is_some() {
                println!("{}", line.text);
            }
            if line.text.starts_with("player ") {
                player = Some(PlayerLine::parse(&line.text));
                world = None;
            } else if line.text.starts_with("world ") {
                if let Some(whole) = world_lines.push(&line.text) {
                    world = Some(whole);
                }
            } else if line.text.starts_with("render ") {
                // The first frame's player line may have gone with the boot's log.
                match &player {
                    Some(player) if player.menu < 0 => {
                        frame(emulator, (player, world.as_ref()), &line.text)
                    }
                    _ => {}
                }
            }
        }
    }
}
