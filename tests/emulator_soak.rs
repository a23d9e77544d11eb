//! Soak: the real game ROM in the real mGBA core, on every shipped map, under random and
//! adversarial buttons: holding into corners, spinning on the spot, mashing jump under low
//! ceilings, crouch-walking, flying at full speed into floors and ceilings, looking to the limits,
//! and the Start menu changing resolution, lighting and every other setting mid-game.
//!
//! The script is written while the host runs the same [`Game`] on it, so a map switch through the
//! menu lands exactly, and every tick is checked on the host with exact geometry
//! ([`check_tick`]: the player strictly inside a valid sector, never through a solid wall). From
//! outside the ROM, every emulator frame, the harness checks:
//! - no panic and no fatal line (the harness fails the frame), and no line mGBA grades as an error
//!   or a game error: byte stores to OAM or OBJ VRAM, bad memory accesses, …;
//! - every `player` line the same pose and state as the host's replay at that tick;
//! - the rows of the page on screen that BG2 shows unchanged since the last flip: the renderer
//!   wrote only the back page (a 120×80 frame shows rows 0..80; the ROM lends the rest to
//!   textures while it does);
//! - guard regions unchanged: the VRAM between and after the two pages, the colormap in OBJ VRAM
//!   and the OBJ VRAM after the column windows (the code copied to VRAM at boot lies in these:
//!   linker.ld's `vram*` regions), OAM, the palette, and the EWRAM above what the ROM uses;
//! - every frame's cycles within [`FRAME_CYCLES_BOUND`];
//! - the stack: the ROM's `stack used=… room=…` lines, and the paint left in IWRAM read by the
//!   host at the end, below the room the linker left.
//!
//! The maps are the ROM's: `PORTALCAST_ASSETS` (and `PORTALCAST_MAPS`) soak a user's maps or a
//! Doom WAD's, with `PORTALCAST_GBA` naming the ROM built from the same assets (`cargo xtest`
//! soaks Freedoom's maps this way: `portalcast_xtask::freedoom`).
//!
//! `PORTALCAST_SOAK_FRAMES` sets the emulator frames per map (default [`SHORT_SOAK_FRAMES`]);
//! the long form, 100,000 frames per map, is
//! `PORTALCAST_SOAK_FRAMES=100000 cargo test --test emulator_soak -- --nocapture`
//! (docs/RELIABILITY.md records its last result). `PORTALCAST_SOAK_KEYS=DIR` also writes each
//! map's buttons, from power-on, to `DIR/MAP.keys`, a key script `pc-run` and `pc-profile`
//! take: a frame of the soak can be replayed and profiled alone.

mod common;

use common::demos::{PlayerLine, WorldLine, WorldLines};
use common::player::check_tick;
use common::{boot, field, number, FRAME_LINES_HOLD, FRAME_LINES_KEY};
use portalcast::player::input::Buttons;
use portalcast::render::walk::ColumnWindows;
use portalcast::stack::{IWRAM_START, STACK_PAINT, STACK_TOP};
use portalcast_harness::{Emulator, KeyScript, Keys, LogLevel};
use portalcast_rom::game::Game;
use portalcast_rom::menu::{Entry, ENTRIES};
// SplitMix64, seeded: the soak is the same run every time.
use portalcast_oracle::Rng;
use std::collections::BTreeSet;

/// Emulator frames per map in the test command's short soak: 100 seconds of play each.
const SHORT_SOAK_FRAMES: u32 = 6000;

/// The longest a frame of the game may take to draw, in CPU cycles: 16 display frames. The
/// bench map's fly-through peaks near 2.7 million cycles at 240×160 (docs/BENCH.md); the soak
/// reaches poses no fly-through does (the eye against a wall or a ceiling, the view along a
/// corridor's full length, looking to the limits), so the bound leaves half again on top. What
/// it must catch is a frame that runs away: a portal loop cut only at the depth limit, a span
/// or column run past its window.
const FRAME_CYCLES_BOUND: u64 = 16 * 280_896;

/// IWRAM the ROM may use: all but the 256 bytes at the top that the BIOS keeps.
const IWRAM_USABLE: u32 = (STACK_TOP - IWRAM_START) as u32;

/// Mode 4's two pages and what surrounds them in VRAM.
const PAGE_BYTES: u32 = 240 * 160;
const PAGE_ADDRESSES: [u32; 2] = [0x0600_0000, 0x0600_A000];
/// Memory the game never writes once it runs, as (what, address, bytes): checked against the
/// contents seen when the game starts.
const GUARDED: [(&str, u32, u32); 6] = [
    (
        "VRAM between the pages",
        0x0600_0000 + PAGE_BYTES,
        0xA000 - PAGE_BYTES,
    ),
    (
        "VRAM after the second page",
        0x0600_A000 + PAGE_BYTES,
        0xA000 - PAGE_BYTES,
    ),
    // The free OBJ VRAM holds the colormap, copied once at boot, then the renderer's column
    // windows (`hw::memory::VramWindows`), which every frame writes; the rest stays untouched.
    ("OBJ VRAM: the colormap", OBJ_VRAM, COLORMAP_BYTES),
    (
        "OBJ VRAM after the column windows",
        OBJ_VRAM + COLORMAP_BYTES + WINDOWS_BYTES,
        0x4000 - COLORMAP_BYTES - WINDOWS_BYTES,
    ),
    ("OAM", 0x0700_0000, 0x400),
    ("the palette", 0x0500_0000, 0x400),
];
/// The OBJ tile VRAM Mode 4 leaves free, and what the ROM keeps at its start.
const OBJ_VRAM: u32 = 0x0601_4000;
const COLORMAP_BYTES: u32 = core::mem::size_of::<portalcast_format::Colormap>() as u32;
const WINDOWS_BYTES: u32 = core::mem::size_of::<ColumnWindows>() as u32;
/// Guard regions are compared every this many frames (reading them costs host time).
const GUARD_CHECK_FRAMES: u32 = 16;
const EWRAM_START: u32 = 0x0200_0000;
const EWRAM_BYTES: u32 = 0x4_0000;
const DISPCNT: u32 = 0x0400_0000;
const DISPCNT_PAGE: u16 = 1 << 4;
/// BG2's step down the page per screen line, 8.8 fixed point: 0x80 shows 80 page rows
/// (120×80), 0x100 all 160.
const BG2PD: u32 = 0x0400_0026;

#[test]
fn every_map_survives_random_and_adversarial_input() {
    let frames = std::env::var("PORTALCAST_SOAK_FRAMES")
        .ok()
        .map(|text| {
            text.parse::<u32>()
                .unwrap_or_else(|_| panic!("PORTALCAST_SOAK_FRAMES={text} is not a frame count"))
        })
        .unwrap_or(SHORT_SOAK_FRAMES);
    let maps: Vec<&'static str> = portalcast_rom::assets::MAPS
        .iter()
        .map(|m| m.name)
        .collect();
    // One emulator per map, on their own threads: the maps are independent runs.
    let reports: Vec<Result<String, String>> = std::thread::scope(|scope| {
        let handles: Vec<_> = maps
            .iter()
            .enumerate()
            .map(|(index, &map)| scope.spawn(move || soak_map(map, index as u64 + 1, frames)))
            .collect();
        handles
            .into_iter()
            .map(|handle| {
                handle
                    .join()
                    .unwrap_or_else(|panic| Err(panic_text(panic.as_ref())))
            })
            .collect()
    });
    let mut failures = Vec::new();
    println!("soak: {frames} emulator frames per map, cycle bound {FRAME_CYCLES_BOUND}");
    println!("| map | frames | ticks | ticks with a mover moving | frames drawn | sectors visited | max cycles (resolution) | flips / unflipped frames compared | IWRAM code and data | stack high-water / room | IWRAM never touched (of {IWRAM_USABLE}) | mGBA warnings |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (map, report) in maps.iter().zip(reports) {
        match report {
            Ok(row) => println!("{row}"),
            Err(error) => failures.push(format!("{map}: {error}")),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

fn panic_text(panic: &(dyn std::any::Any + Send)) -> String {
    panic
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_else(|| "panicked".to_owned())
}

/// Boots the ROM, steers the game to `map` through the menu, then plays `frames` frames of
/// adversarial input, checking everything the module doc lists. Returns a table row.
fn soak_map(map: &'static str, seed: u64, frames: u32) -> Result<String, String> {
    let mut emulator = boot();
    let start = run_until_game_starts(&mut emulator)?;
    let boot_line = emulator
        .debug_lines()
        .into_iter()
        .find(|line| line.starts_with("portalcast boot"))
        .ok_or("no boot line")?
        .to_owned();
    let iwram_used = number(&boot_line, "iwram_used") as u32;
    let stack_room = number(&boot_line, "stack_room") as u32;
    // The EWRAM the game was handed (its linked statics and what it took at start), final by
    // its start line.
    let start_line = emulator
        .debug_lines()
        .into_iter()
        .find(|line| line.starts_with("play start"))
        .ok_or("no play start line")?
        .to_owned();
    let ewram_used = number(&start_line, "ewram_used") as u32;
    assert!(ewram_used >= number(&boot_line, "ewram_used") as u32);

    // More ticks than the frames left: the ROM's last frame may run a tick or two past them.
    let ticks = frames + 64;
    let plan = Plan::write(map, seed, ticks);
    let script = plan.script(start);
    if let Some(directory) = std::env::var_os("PORTALCAST_SOAK_KEYS") {
        let path = std::path::Path::new(&directory).join(format!("{map}.keys"));
        let boot = KeyScript::new().hold(FRAME_LINES_HOLD, FRAME_LINES_KEY);
        std::fs::create_dir_all(&directory)
            .and_then(|()| std::fs::write(&path, format!("{boot}{script}")))
            .map_err(|error| format!("writing {}: {error}", path.display()))?;
    }

    let guarded: Vec<(&str, u32, u32)> = GUARDED
        .into_iter()
        .chain([(
            "EWRAM above the ROM's",
            EWRAM_START + ewram_used,
            EWRAM_BYTES - ewram_used,
        )])
        .collect();
    let guard_contents: Vec<Vec<u8>> = guarded
        .iter()
        .map(|&(_, address, bytes)| emulator.read_bytes(address, bytes as usize))
        .collect();

    let mut shown = Shown::read(&emulator);
    let (mut pages_compared, mut flips) = (0u64, 0u64);
    let mut max_cycles = (0u64, String::new());
    let mut stack_used_rom = 0u32;
    // The linker script's STACK_RESERVE, as the ROM prints it; the room until a line says.
    let mut stack_reserve = stack_room;
    let mut sectors = BTreeSet::new();
    let mut drawn = 0u64;
    let mut last_tick = 0u32;
    let mut warnings = 0u64;
    let mut world_lines = 0u64;
    let mut world_parts = WorldLines::default();
    let mut recent: Vec<String> = Vec::new();
    while (emulator.frames_run() as u32) < frames {
        let frame = emulator.frames_run() as u32;
        emulator.set_keys(script.keys_at(frame));
        let result = emulator.run_frame();
        let lines = emulator.drain_log();
        for line in &lines {
            if line.is_debug_print() {
                recent.push(line.text.clone());
            }
        }
        if recent.len() > 12 {
            recent.drain(..recent.len() - 12);
        }
        let context = || {
            format!(
                "frame {frame}; the ROM's last lines:\n  {}",
                recent.join("\n  ")
            )
        };
        result.map_err(|error| format!("{error}\n{}", context()))?;
        for line in &lines {
            match line.level {
                LogLevel::Error | LogLevel::GameError => {
                    return Err(format!("mGBA: {line}\n{}", context()))
                }
                LogLevel::Warn | LogLevel::Stub => warnings += 1,
                _ => {}
            }
            if !line.is_debug_print() {
                continue;
            }
            let text = line.text.as_str();
            if text.starts_with("player ") {
                let logged = PlayerLine::parse(text);
                let host = plan.state_after(logged.tick).ok_or_else(|| {
                    format!("tick {} is past the plan\n{}", logged.tick, context())
                })?;
                let expected = PlayerLine::of(host);
                if !logged.same_state(&expected) || logged.lost != 0 {
                    return Err(format!(
                        "the ROM and the host differ after tick {}:\n  rom:  {text}\n  host: {expected:?}\n{}",
                        logged.tick,
                        context()
                    ));
                }
                sectors.insert(logged.sector);
                last_tick = logged.tick;
            } else if let Some(rest) = text.strip_prefix("world ") {
                // The live world the frame drew: the movers' heights, the switches and the
                // light levels as the host's game has them after the same tick (in parts: the
                // last one completes it).
                let host = plan
                    .state_after(last_tick)
                    .ok_or("a world line before any player")?;
                let Some(rom) = world_parts.push(rest) else {
                    continue;
                };
                let expected = WorldLine::of(host);
                if rom != expected {
                    return Err(format!(
                        "the ROM's world and the host's differ after tick {last_tick}:\n  rom:  {text}\n  host: {expected:?}\n{}",
                        context()
                    ));
                }
                world_lines += 1;
            } else if text.starts_with("render ") {
                drawn += 1;
                let cycles = number(text, "cycles");
                if cycles > max_cycles.0 {
                    let resolution = field(text, "res").unwrap_or("?").to_owned();
                    max_cycles = (cycles, resolution);
                }
                if cycles > FRAME_CYCLES_BOUND {
                    return Err(format!(
                        "a frame took {cycles} cycles, over the bound {FRAME_CYCLES_BOUND}: {text}\n{}",
                        context()
                    ));
                }
            } else if text.starts_with("stack ") {
                let used = number(text, "used") as u32;
                let room = number(text, "room") as u32;
                stack_reserve = number(text, "reserve") as u32;
                stack_used_rom = stack_used_rom.max(used);
                if used >= room.min(stack_reserve) {
                    return Err(format!(
                        "the stack reached the linker's reserve or its room: {text}\n{}",
                        context()
                    ));
                }
            }
        }
        // The page on screen: unchanged unless the ROM flipped to the other one.
        let now = Shown::read(&emulator);
        if now.page == shown.page {
            if now.bytes != shown.bytes {
                let first = now
                    .bytes
                    .iter()
                    .zip(&shown.bytes)
                    .position(|(a, b)| a != b)
                    .unwrap_or(0);
                return Err(format!(
                    "the page on screen (0x{:08x}) changed at offset {first} without a flip\n{}",
                    PAGE_ADDRESSES[now.page],
                    context()
                ));
            }
            pages_compared += 1;
        } else {
            flips += 1;
        }
        shown = now;
        if frame.is_multiple_of(GUARD_CHECK_FRAMES) {
            for ((what, address, bytes), before) in guarded.iter().zip(&guard_contents) {
                let now = emulator.read_bytes(*address, *bytes as usize);
                if let Some(offset) = now.iter().zip(before).position(|(a, b)| a != b) {
                    return Err(format!(
                        "{what} was written: 0x{:08x} changed\n{}",
                        address + offset as u32,
                        context()
                    ));
                }
            }
        }
    }
    let stack_used_host = host_stack_high_water(&emulator, iwram_used);
    if stack_used_host >= stack_room.min(stack_reserve) {
        return Err(format!(
            "the stack reached {stack_used_host} bytes: past the linker's reserve ({stack_reserve}) or the room ({stack_room})"
        ));
    }
    if stack_used_rom > stack_used_host {
        return Err(format!(
            "the ROM reports {stack_used_rom} bytes of stack used, the paint shows {stack_used_host}"
        ));
    }
    if drawn < 10 || sectors.len() < 2 {
        return Err(format!(
            "the soak hardly played: {drawn} frames drawn, sectors {sectors:?}"
        ));
    }
    // A map with movers (every shipped one: issue 18, `tests/live_flight.rs`) is played with
    // its movers running, checked every tick like the player, and a map with movers or light
    // effects prints its world with every frame. A user's map (`PORTALCAST_ASSETS`, the
    // generated ones of issue 16) may have neither.
    let on_map = plan.states[..=last_tick as usize]
        .iter()
        .filter(|game| game.map_name() == map);
    let (has_movers, live) = on_map.clone().next().map_or((false, false), |game| {
        (!game.world.movers().is_empty(), game.world.is_live())
    });
    let moving_ticks = on_map
        .filter(|game| {
            game.world
                .movers()
                .iter()
                .any(|mover| mover.phase != portalcast::world::Phase::Resting)
        })
        .count();
    // The shipped maps put a door or a lift within the random walk's reach; a Doom map's lie
    // far from its start (issue 19: E1M1's nearest door is rooms away), so there the soak
    // checks only that the ROM drew every frame with its world.
    let doors_within_reach = !portalcast_assets::doom::is_map_name(map);
    if (has_movers && moving_ticks == 0 && doors_within_reach) || (live && world_lines < drawn) {
        return Err(format!(
            "the movers never moved ({moving_ticks} ticks with one away from rest) or the ROM drew frames without its world ({world_lines} world lines, {drawn} frames)"
        ));
    }
    Ok(format!(
        "| {map} | {frames} | {} | {moving_ticks} | {drawn} | {} | {} ({}) | {flips} / {pages_compared} | {iwram_used} | {stack_used_host} / {stack_room} | {} | {warnings} |",
        last_tick,
        sectors.len(),
        max_cycles.0,
        max_cycles.1,
        stack_room - stack_used_host,
    ))
}

/// Runs frames until the ROM starts the game, with its per-frame lines switched on (the soak
/// reads every `player` and `render` line) and no other key; returns the VBlank it started at.
fn run_until_game_starts(emulator: &mut Emulator) -> Result<u32, String> {
    for frame in 0..120 {
        emulator.set_keys(if FRAME_LINES_HOLD.contains(&frame) {
            FRAME_LINES_KEY
        } else {
            Keys::NONE
        });
        emulator.run_frame().map_err(|error| error.to_string())?;
        if let Some(line) = emulator
            .debug_lines()
            .into_iter()
            .find(|line| line.starts_with("play start"))
        {
            return Ok(number(line, "vblank") as u32);
        }
    }
    Err("the game did not start within 120 frames".to_owned())
}

/// The page on screen and its bytes.
/// The page on screen and the bytes of the rows BG2 shows of it: at 120×80 its rows 80..160
/// are not on screen, and the ROM lends them to textures (`hw::memory::LentPageRows`).
struct Shown {
    page: usize,
    bytes: Vec<u8>,
}

impl Shown {
    fn read(emulator: &Emulator) -> Shown {
        let page = usize::from(emulator.read_u16(DISPCNT) & DISPCNT_PAGE != 0);
        let step = u32::from(emulator.read_u16(BG2PD)).clamp(1, 0x100);
        let rows = (160 * step).div_ceil(0x100);
        Shown {
            page,
            bytes: emulator.read_bytes(PAGE_ADDRESSES[page], (PAGE_BYTES / 160 * rows) as usize),
        }
    }
}

/// How deep the stack has been, from the paint the boot code left: the distance from the stack
/// top to the lowest word that lost it. Read by the host, independently of the ROM's own count.
fn host_stack_high_water(emulator: &Emulator, iwram_used: u32) -> u32 {
    let top = STACK_TOP as u32;
    let mut address = (IWRAM_START as u32 + iwram_used + 3) & !3;
    while address < top && emulator.read_u32(address) == STACK_PAINT {
        address += 4;
    }
    top - address
}

/// The buttons of every tick, and the game after every tick, written together: each choice
/// looks at the game as it is, so menu moves and map switches land exactly.
struct Plan {
    /// `keys[j]`: the buttons of tick `j + 1`.
    keys: Vec<u16>,
    /// `states[j]`: the game after `j` ticks.
    states: Vec<Game<'static>>,
    rng: Rng,
}

impl Plan {
    fn write(map: &str, seed: u64, ticks: u32) -> Plan {
        let mut plan = Plan {
            keys: Vec::new(),
            states: vec![Game::new(portalcast_rom::assets::MAPS)],
            rng: Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15)),
        };
        // Idle first: the game may have ticked once or twice before the script takes over.
        plan.hold(0, 8);
        plan.switch_to(map);
        while plan.ticks() < ticks {
            plan.adversarial_segment(map);
        }
        plan.keys.truncate(ticks as usize);
        plan.states.truncate(ticks as usize + 1);
        plan
    }

    fn ticks(&self) -> u32 {
        self.keys.len() as u32
    }

    fn game(&self) -> &Game<'static> {
        self.states.last().expect("the initial state")
    }

    fn state_after(&self, tick: u32) -> Option<&Game<'static>> {
        self.states.get(tick as usize)
    }

    /// Holds `held` for `ticks` ticks, checking each tick's move on the host.
    fn hold(&mut self, held: u16, ticks: u32) {
        for _ in 0..ticks {
            let mut game = *self.game();
            let before = game.player;
            let map_before = game.map_name();
            game.tick(Buttons(held));
            if !game.menu.open && !self.game().menu.open && game.map_name() == map_before {
                if let Err(problem) = check_tick(&game.map(), &before, &game.player) {
                    panic!(
                        "the host's game broke an invariant at tick {} on {map_before} (keys 0x{held:03x}): {problem}",
                        game.ticks()
                    );
                }
                // Never crushed: a ceiling that came down keeps the headroom over the eye (an
                // open ceiling's, the one above it).
                let position = game.player.position;
                let ceiling = portalcast::player::collide::open_heights_at(
                    &game.map(),
                    game.player.sector,
                    (position.x.to_bits(), position.y.to_bits()),
                )
                .1;
                assert!(
                    game.player.eye_z().to_bits() + game.player.size.headroom() * 256 <= ceiling,
                    "tick {} on {map_before}: the eye {} under the ceiling {ceiling}",
                    game.ticks(),
                    game.player.eye_z().to_bits()
                );
            }
            self.keys.push(held);
            self.states.push(game);
        }
    }

    /// A press: `held` for one tick, then one tick of nothing, so the next press is an edge.
    fn press(&mut self, held: u16) {
        self.hold(held, 1);
        self.hold(0, 1);
    }

    /// Opens the menu, puts the cursor on the map entry and steps maps until `map`, closes it.
    fn switch_to(&mut self, map: &str) {
        if self.game().map_name() == map {
            return;
        }
        let entry = ENTRIES
            .iter()
            .position(|&entry| entry == Entry::Map)
            .expect("the menu has a map entry");
        self.press(Buttons::START.0);
        while self.game().menu.cursor != entry {
            self.press(Buttons::DOWN.0);
        }
        for _ in 0..portalcast_rom::assets::MAPS.len() {
            if self.game().map_name() == map {
                break;
            }
            self.press(Buttons::RIGHT.0);
        }
        assert_eq!(self.game().map_name(), map, "the menu reaches every map");
        self.press(Buttons::START.0);
    }

    fn adversarial_segment(&mut self, map: &str) {
        const MOVES: [u16; 9] = [
            0,
            Buttons::UP.0,
            Buttons::DOWN.0,
            Buttons::LEFT.0,
            Buttons::RIGHT.0,
            Buttons::UP.0 | Buttons::LEFT.0,
            Buttons::UP.0 | Buttons::RIGHT.0,
            Buttons::UP.0 | Buttons::L.0,
            Buttons::DOWN.0 | Buttons::R.0,
        ];
        let ticks = 20 + self.rng.below(200) as u32;
        match self.rng.below(10) {
            // Random walking, strafing and turning.
            0 => {
                let mut left = ticks;
                while left > 0 {
                    let run = (4 + self.rng.below(40) as u32).min(left);
                    let held = MOVES[self.rng.below(MOVES.len() as u64) as usize];
                    self.hold(held, run);
                    left -= run;
                }
            }
            // Into a wall or a corner at full speed, and on, turning a little to slide along.
            1 => {
                self.hold(Buttons::UP.0, ticks);
                let turn = if self.rng.below(2) == 0 {
                    Buttons::LEFT.0
                } else {
                    Buttons::RIGHT.0
                };
                let slide = 4 + self.rng.below(12) as u32;
                self.hold(Buttons::UP.0 | turn, slide);
                self.hold(Buttons::UP.0, ticks);
            }
            // Spinning on the spot (on a vertex when the last segment ended in a corner).
            2 => {
                let spin = if self.rng.below(2) == 0 {
                    Buttons::LEFT.0
                } else {
                    Buttons::RIGHT.0
                };
                self.hold(spin, ticks);
                self.hold(spin | Buttons::UP.0, ticks / 2);
            }
            // Jumping over and over, walking (under low ceilings and over ledges).
            3 => {
                for _ in 0..ticks / 6 {
                    self.hold(Buttons::UP.0 | Buttons::A.0, 2);
                    self.hold(Buttons::UP.0, 4);
                }
            }
            // Crouch-walking and jumping while crouched.
            4 => {
                self.hold(Buttons::B.0 | Buttons::UP.0, ticks);
                self.hold(Buttons::B.0 | Buttons::A.0 | Buttons::UP.0, 10);
            }
            // Fly mode at full running speed: up into the ceiling, down into the floor, then
            // flying off so the player falls.
            5 => {
                if !self.game().controls.always_run {
                    // Select + B toggles running.
                    self.hold(Buttons::SELECT.0, 1);
                    self.press(Buttons::SELECT.0 | Buttons::B.0);
                }
                if !self.game().player.fly {
                    self.press(Buttons::SELECT.0);
                }
                self.hold(Buttons::UP.0 | Buttons::A.0, ticks);
                self.hold(Buttons::UP.0 | Buttons::LEFT.0 | Buttons::B.0, ticks / 2);
                if self.rng.below(2) == 0 {
                    self.press(Buttons::SELECT.0);
                }
            }
            // Looking to the limits while moving, then re-centring.
            6 => {
                let look = if self.rng.below(2) == 0 {
                    Buttons::UP.0
                } else {
                    Buttons::DOWN.0
                };
                self.hold(Buttons::SELECT.0 | look, ticks / 2);
                self.hold(Buttons::SELECT.0, 1);
                self.hold(Buttons::UP.0, ticks / 2);
                self.press(Buttons::SELECT.0 | Buttons::A.0);
            }
            // Walking and using (L + R) what is in front: doors, lifts and switches, turning a
            // little between uses.
            9 => {
                for _ in 0..ticks / 12 {
                    let walk = 6 + self.rng.below(12) as u32;
                    self.hold(Buttons::UP.0, walk);
                    self.hold(Buttons::L.0 | Buttons::R.0, 2);
                    let turn = if self.rng.below(2) == 0 {
                        Buttons::LEFT.0
                    } else {
                        Buttons::RIGHT.0
                    };
                    let turning = self.rng.below(12) as u32;
                    self.hold(turn, turning);
                }
            }
            // The menu: random moves and changes, except the map (the soak stays on `map`).
            7 => {
                self.press(Buttons::START.0);
                for _ in 0..3 + self.rng.below(10) {
                    let on_map = ENTRIES[self.game().menu.cursor] == Entry::Map;
                    let key = match self.rng.below(5) {
                        0 => Buttons::UP.0,
                        1 => Buttons::DOWN.0,
                        _ if on_map => Buttons::DOWN.0,
                        2 => Buttons::LEFT.0,
                        3 => Buttons::RIGHT.0,
                        _ => Buttons::A.0,
                    };
                    self.press(key);
                }
                self.press(Buttons::START.0);
            }
            // Mashing: every button but Start, changing every few ticks.
            _ => {
                let mut left = ticks;
                while left > 0 {
                    let run = (1 + self.rng.below(6) as u32).min(left);
                    let held = self.rng.below(0x400) as u16 & !Buttons::START.0;
                    self.hold(held, run);
                    left -= run;
                }
            }
        }
        assert_eq!(self.game().map_name(), map, "the soak stays on its map");
    }

    /// The harness script: tick `j` reads the buttons of emulator frame `start + j`.
    fn script(&self, start: u32) -> KeyScript {
        let mut changes = Vec::new();
        let mut last = None;
        for (index, &held) in self.keys.iter().enumerate() {
            if last != Some(held) {
                changes.push((start + 1 + index as u32, Keys::from_bits_truncate(held)));
                last = Some(held);
            }
        }
        KeyScript::from_changes(changes)
    }
}
