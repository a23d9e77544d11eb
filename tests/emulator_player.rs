//! The player in the ROM under the real mGBA core, driven by scripted key demos: the jump's
//! eye height, the sector after climbing the stairs, a step too tall, crouching under a low
//! ceiling, fly mode, the bench map's movers (a door walked through, a lift ridden up and down,
//! a switch thrown, a closing door turning back at the body: issue 18), and determinism: the
//! same demo, or the ROM's own recording of it, gives the same log and the same screens.
//!
//! Every demo also checks that each pose the ROM logs is the pose the host's game reaches after
//! the same ticks of the same script (`common::demos::replay`): the ROM and the host run the
//! same integer code, so a demo is a key sequence and gives the same positions everywhere. And
//! `cargo play`'s demo, through the door and on the lift, is compared frame by frame: each VRAM
//! page the ROM draws is the host's render of its logged pose and world.

mod common;

use common::demos::{replay, PlayerLine, WorldLine, WorldLines};
use common::player::sector_index;
use common::rom_frames::{boot_until_playing, host_frame_matching, play_frames};
use common::*;
use portalcast::player::vertical::{CROUCH_EYE, JUMP_RISE, STAND_EYE};
use portalcast::render::walk::Renderer;
use portalcast::world::Phase;
use portalcast_format::TRIGGER_THROWN;
use portalcast_harness::{KeyScript, Keys};
use portalcast_rom::game::Game;

/// What one run of a demo in the ROM left behind.
struct RomRun {
    /// The VBlank the game started at (`play start vblank=`).
    start: u32,
    /// Every `player` line, in order.
    lines: Vec<PlayerLine>,
    /// Every debug line of the run.
    log: Vec<String>,
    /// A hash of the screen after every emulator frame.
    screens: Vec<u64>,
    /// The game on the host after every tick of the same script.
    host: Vec<Game<'static>>,
}

impl RomRun {
    /// The last logged line.
    fn last(&self) -> &PlayerLine {
        self.lines.last().expect("the ROM logged its player")
    }

    /// Host states at every tick from the first to the last the ROM logged.
    fn host_ticks(&self) -> &[Game<'static>] {
        &self.host[..=self.last().tick as usize]
    }
}

/// Plays `script` for `frames` emulator frames from power-on, and checks every logged pose
/// against the host's replay.
fn play(script: &str, frames: u32) -> RomRun {
    play_script(
        &KeyScript::parse(script).unwrap_or_else(|error| panic!("{error}")),
        frames,
    )
}

/// [`play`] with a parsed script, the ROM's per-frame lines switched on (the poses are read from
/// its `player` lines).
fn play_script(script: &KeyScript, frames: u32) -> RomRun {
    let script = &with_frame_lines(script);
    let mut emulator = boot();
    let mut screens = Vec::new();
    for frame in 0..frames {
        emulator.set_keys(script.keys_at(frame));
        emulator
            .run_frame()
            .unwrap_or_else(|error| panic!("{error}"));
        let mut hasher = std::collections::hash_map::DefaultHasher::new();
        std::hash::Hash::hash(&emulator.frame_rgb().into_raw(), &mut hasher);
        screens.push(std::hash::Hasher::finish(&hasher));
    }
    let log: Vec<String> = emulator
        .debug_lines()
        .into_iter()
        .map(str::to_owned)
        .collect();
    let start_line = log
        .iter()
        .find(|line| line.starts_with("play start"))
        .expect("the ROM starts the game");
    let start = number(start_line, "vblank") as u32;
    let lines: Vec<PlayerLine> = log
        .iter()
        .filter(|line| line.starts_with("player "))
        .map(|line| PlayerLine::parse(line))
        .collect();
    assert!(lines.len() >= 10, "only {} frames drawn", lines.len());
    let last_tick = lines.last().unwrap().tick;
    let host = replay(script, start, last_tick);
    for line in &lines {
        assert_eq!(line.lost, 0, "the ROM lost input samples: {}", line.text);
        let expected = PlayerLine::of(&host[line.tick as usize]);
        assert!(
            line.same_state(&expected),
            "the ROM and the host differ after tick {}:\n  rom:  {}\n  host: {expected:?}",
            line.tick,
            line.text
        );
    }
    RomRun {
        start,
        lines,
        log,
        screens,
        host,
    }
}

/// The floor under the logged pose.
fn floor_bits(line: &PlayerLine) -> i32 {
    portalcast_rom::demo::demo_map().sectors[usize::from(line.sector)].floor_z * 256
}

#[test]
fn a_jump_lifts_the_eye_to_48_above_the_floor_and_lands() {
    // A tap of A after a second of standing.
    let run = play("60-61: A\n", 150);
    // On the host, tick by tick: the apex is exactly 48 above the floor.
    let above_floor: Vec<i32> = run
        .host_ticks()
        .iter()
        .map(|game| {
            let line = PlayerLine::of(game);
            line.z - floor_bits(&line)
        })
        .collect();
    let apex = (STAND_EYE + JUMP_RISE) * 256;
    assert_eq!(*above_floor.iter().max().unwrap(), apex);
    assert_eq!(above_floor.iter().filter(|&&h| h == apex).count(), 1);
    // In the ROM's frames: airborne at some frame, never above 48, back on the floor at 32.
    let airborne: Vec<&PlayerLine> = run.lines.iter().filter(|line| !line.ground).collect();
    assert!(!airborne.is_empty(), "no frame caught the jump");
    for line in &run.lines {
        let above = line.z - floor_bits(line);
        assert!(
            (STAND_EYE * 256..=(STAND_EYE + JUMP_RISE) * 256).contains(&above),
            "{}",
            line.text
        );
    }
    assert!(airborne.iter().any(|line| line.z > (STAND_EYE + 8) * 256));
    let last = run.last();
    assert!(last.ground);
    assert_eq!(last.z - floor_bits(last), STAND_EYE * 256);
}

#[test]
fn climbing_the_stairs_ends_on_the_top_landing() {
    // Run on (Select + B), north onto the dais (a step right first, past the statue), a
    // right-angle turn east, along the corridor to the lower landing's east wall, a turn
    // north, up the eight steps to the top landing.
    let script = "
10-13: SELECT
11-12: B
20-32: R
20-72: UP
100-135: RIGHT
150-420: UP
440-475: LEFT
490-600: UP
";
    let run = play(script, 640);
    let landing_top = sector_index("bench.map", "landing_top");
    let last = run.last();
    assert_eq!(last.sector, landing_top, "{}", last.text);
    assert!(last.ground);
    assert_eq!(
        last.z,
        (128 + STAND_EYE) * 256,
        "eye 32 above the top floor"
    );
    // The host's ticks went up every step in order.
    let steps: Vec<u16> = (1..=8)
        .map(|k| sector_index("bench.map", &format!("step_{k}")))
        .collect();
    let mut visited: Vec<u16> = Vec::new();
    for game in run.host_ticks() {
        let sector = game.player.sector;
        if steps.contains(&sector) && visited.last() != Some(&sector) {
            visited.push(sector);
        }
    }
    assert_eq!(visited, steps);
}

#[test]
fn a_step_too_tall_blocks_the_player_and_a_jump_climbs_it() {
    // Strafe right in front of the 24-high ledge, walk back into it, then jump back onto it.
    let script = "
20-45: R
70-150: DOWN
160-200: DOWN
165-167: A
";
    let run = play(script, 260);
    let hall_s = sector_index("bench.map", "hall_s");
    let ledge = sector_index("bench.map", "ledge");
    let blocked: Vec<&PlayerLine> = run
        .lines
        .iter()
        .filter(|line| (100..=150).contains(&(line.tick + run.start)))
        .collect();
    assert!(!blocked.is_empty());
    for line in blocked {
        assert_eq!(line.sector, hall_s, "{}", line.text);
        assert_eq!(
            line.y,
            752 * 256,
            "one radius before the ledge: {}",
            line.text
        );
        assert_eq!(line.z, STAND_EYE * 256, "{}", line.text);
    }
    let last = run.last();
    assert_eq!(last.sector, ledge, "{}", last.text);
    assert_eq!(last.z, (24 + STAND_EYE) * 256);
}

#[test]
fn crouching_passes_under_a_low_ceiling() {
    // Strafe left in front of the crawlway (40 high), walk back into it standing (blocked),
    // crouch and go in, let go of B inside (the eye stays 16 under the ceiling), crouch on into
    // the den.
    let script = "
20-45: L
70-130: DOWN
140-200: DOWN+B
210-240: NONE
250-340: DOWN+B
";
    let run = play(script, 380);
    let hall_s = sector_index("bench.map", "hall_s");
    let crawl = sector_index("bench.map", "crawl");
    let den = sector_index("bench.map", "den");
    let at_frame = |frame: u32| {
        run.lines
            .iter()
            .rev()
            .find(|line| line.tick + run.start <= frame)
            .unwrap_or_else(|| panic!("no frame before {frame}"))
    };
    let standing = at_frame(130);
    assert_eq!(standing.sector, hall_s, "{}", standing.text);
    assert_eq!(standing.y, 752 * 256, "{}", standing.text);
    assert!(!standing.crouch);
    let crouched = at_frame(200);
    assert_eq!(crouched.sector, crawl, "{}", crouched.text);
    assert_eq!(crouched.z, CROUCH_EYE * 256, "{}", crouched.text);
    assert!(crouched.crouch);
    let let_go = at_frame(240);
    assert_eq!(let_go.sector, crawl, "{}", let_go.text);
    assert_eq!(let_go.z, (40 - 16) * 256, "{}", let_go.text);
    assert!(let_go.crouch, "the ceiling keeps the player down");
    let last = run.last();
    assert_eq!(last.sector, den, "{}", last.text);
}

#[test]
fn fly_mode_rises_to_the_ceiling_descends_and_falls_when_switched_off() {
    // Tap Select (fly on), hold A (rise), hold B (descend), rise a little, tap Select (off).
    let script = "
20-22: SELECT
30-130: A
140-240: B
250-270: A
280-282: SELECT
";
    let run = play(script, 340);
    let at_frame = |frame: u32| {
        run.lines
            .iter()
            .rev()
            .find(|line| line.tick + run.start <= frame)
            .unwrap()
    };
    let high = at_frame(130);
    assert!(high.fly, "{}", high.text);
    assert_eq!(
        high.z,
        (192 - 16) * 256,
        "16 under the hall's ceiling: {}",
        high.text
    );
    let low = at_frame(240);
    assert!(low.fly);
    assert_eq!(low.z, STAND_EYE * 256, "{}", low.text);
    let lifted = at_frame(278);
    assert!(
        lifted.fly && lifted.z > (STAND_EYE + 32) * 256,
        "{}",
        lifted.text
    );
    let last = run.last();
    assert!(!last.fly && last.ground, "{}", last.text);
    assert_eq!(last.z, STAND_EYE * 256);
    assert!(
        run.lines.iter().any(|line| !line.fly && !line.ground),
        "a frame shows the fall"
    );
}

#[test]
fn the_same_demo_twice_and_its_recording_give_the_same_poses_and_frames() {
    // Walking, turning, strafing, a jump, looking up and re-centring, the menu (resolution to
    // 120x160 and back), crouching, fly mode.
    let script = "
20-80: UP
40-70: RIGHT
90-120: L
100-102: A
130-150: SELECT
132-148: UP
152-154: SELECT
153: A
160-161: START
170-171: RIGHT
180-181: START
190-230: UP+B
240-241: START
245-246: LEFT
250-251: START
260-262: SELECT
270-300: A
";
    let first = play(script, 320);
    let second = play(script, 320);
    assert_eq!(first.log, second.log, "the logs differ");
    assert_eq!(first.screens, second.screens, "the screens differ");
    // The ROM's recording of its buttons (`input` lines, and the boot keys that switched its
    // per-frame lines on) replays the same game.
    let recorded = KeyScript::from_rom_log(first.log.iter().map(String::as_str));
    let original = KeyScript::parse(script).unwrap();
    for frame in first.start + 1..320 {
        assert_eq!(
            recorded.keys_at(frame),
            original.keys_at(frame),
            "frame {frame}"
        );
    }
    let third = play_script(&recorded, 320);
    assert_eq!(first.log, third.log, "the recording's log differs");
    assert_eq!(
        first.screens, third.screens,
        "the recording's screens differ"
    );
    // The demo did what it says: moved, looked up, opened the menu, flew.
    assert!(first.lines.iter().any(|line| line.look > 0));
    assert!(first.lines.iter().any(|line| line.menu >= 0));
    assert!(first.log.iter().any(|line| line.contains("res=120x160")));
    assert!(first.last().fly);
}

#[test]
fn the_tick_benchmark_walk_turns_strafes_jumps_and_slides_along_walls() {
    // `cargo bench-tick` times the ROM's ticks along this walk: its figures stand for play only
    // if the walk has the collisions as well as free motion. Played here, every pose is also
    // checked against the host's replay.
    use common::player::{distance_to_segment, solid_walls, units};
    use portalcast::player::collide::RADIUS;
    use portalcast::player::input::Buttons;
    use portalcast_xtask::bench_tick::{FRAMES, KEYS_FILE};

    let script = KeyScript::load(&portalcast_xtask::workspace_root().join(KEYS_FILE))
        .unwrap_or_else(|error| panic!("{error}"));
    let run = play_script(&script, FRAMES);
    let map = portalcast_rom::demo::demo_map();
    let walls: Vec<((f64, f64), (f64, f64))> = solid_walls(&map)
        .into_iter()
        .map(|(a, b)| {
            let point =
                |p: portalcast::math::WorldPoint| (units(p.x.to_bits()), units(p.y.to_bits()));
            (point(a), point(b))
        })
        .collect();
    let (mut turns, mut strafes, mut jumps, mut slides) = (0, 0, 0, 0);
    for pair in run.host_ticks().windows(2) {
        let (before, after) = (&pair[0].player, &pair[1].player);
        let moved = after.position != before.position;
        let centre = (
            units(after.position.x.to_bits()),
            units(after.position.y.to_bits()),
        );
        let touching = walls
            .iter()
            .any(|&(a, b)| distance_to_segment(centre, a, b) < f64::from(RADIUS) + 1.0 / 16.0);
        turns += usize::from(after.angle != before.angle);
        strafes += usize::from(moved && pair[1].held().any(Buttons(Buttons::L.0 | Buttons::R.0)));
        jumps += usize::from(before.on_ground && !after.on_ground && !after.fly);
        slides += usize::from(moved && touching);
    }
    assert!(turns >= 100, "{turns} ticks turned");
    assert!(strafes >= 100, "{strafes} ticks strafed");
    assert!(jumps >= 5, "{jumps} jumps");
    assert!(slides >= 100, "{slides} ticks slid along a wall");
}

/// Whether the door is at least the standing body's height whenever the body is under it.
fn door_height_ok(run: &RomRun, tick: u32) -> bool {
    let game = &run.host[tick as usize];
    game.world.movers()[0].height >= 48
}

/// The movers' heights the ROM logged after each `player` line (`world frame=F heights=…`),
/// checked against the host's game at the same tick, in order; the switches the line gives as
/// thrown (`thrown=…`) and the light effects' levels (`lights=…`) are checked too.
fn checked_mover_heights(run: &RomRun) -> Vec<(u32, Vec<i32>)> {
    let mut heights = Vec::new();
    let mut tick = None;
    let mut parts = WorldLines::default();
    for line in &run.log {
        if line.starts_with("player ") {
            tick = Some(PlayerLine::parse(line).tick);
        } else if line.starts_with("world ") {
            let tick = tick.expect("a player line before the world line");
            let Some(logged) = parts.push(line) else {
                continue;
            };
            let host = WorldLine::of(&run.host[tick as usize]);
            assert_eq!(logged, host, "the world after tick {tick}: {line}");
            let logged = logged.heights;
            heights.push((tick, logged));
        }
    }
    assert!(!heights.is_empty(), "the ROM logged no movers");
    heights
}

/// `cargo play`'s demo, `assets/demo/play.keys`: through the bench map's door and on its lift.
fn demo_script() -> KeyScript {
    KeyScript::load(&portalcast_xtask::workspace_root().join("assets/demo/play.keys"))
        .unwrap_or_else(|error| panic!("{error}"))
}

#[test]
fn a_walk_opens_the_door_passes_it_and_rides_the_lift_up_and_down() {
    // The demo (`assets/demo/play.keys`, what `cargo play` presses): the stairs walk's way east
    // (run on, onto the dais, a turn east); the corridor's door opens as the body walks into it,
    // and the walk goes through, to the lower landing's east side. There, L + R lowers the lift
    // in front; a few steps onto it; it comes back up with the body after its wait; L + R
    // again, standing on it: down, and up once more.
    let run = play_script(&demo_script(), 1150);
    let heights = checked_mover_heights(&run);
    let corridor = sector_index("bench.map", "corridor_1");
    let lift = sector_index("bench.map", "lift");
    let door_open = heights.iter().any(|(_, h)| h[0] == 96);
    assert!(door_open, "the door never opened");
    assert!(
        run.host_ticks()
            .iter()
            .any(|game| game.player.sector == corridor),
        "the walk never went through the door"
    );
    // On the lift: carried up to 128 and down to 0 again, standing.
    let on_lift: Vec<&Game> = run
        .host_ticks()
        .iter()
        .filter(|game| game.player.sector == lift)
        .collect();
    let feet = |game: &&Game| game.player.feet_z.to_bits();
    let up = on_lift.iter().position(|game| feet(game) == 128 * 256);
    let down_again = up.and_then(|at| on_lift[at..].iter().position(|game| feet(game) == 0));
    assert!(
        up.is_some() && down_again.is_some(),
        "the lift did not carry the body up and down"
    );
    assert!(on_lift.iter().all(|game| game.player.on_ground));
    let last = run.last();
    assert_eq!(last.sector, lift, "{}", last.text);
}

#[test]
fn the_switch_opens_the_door_and_the_closing_door_turns_back_at_the_body() {
    // North on the dais further than the stairs walk, east to the hall's east wall beside the
    // door, out of its touch: L + R throws the switch there, which opens the door (tag 1). A walk
    // south-east, sliding along the wall, through the doorway, to stop just past it with the
    // body still under the door: when the door comes down to it, it goes back up.
    let script = "
10-13: SELECT
11-12: B
20-32: R
20-88: UP
100-135: RIGHT
150-230: UP
240-243: L+R
250-266: RIGHT
270-292: UP
";
    let run = play(script, 560);
    let heights = checked_mover_heights(&run);
    let door: Vec<(u32, i32)> = heights.iter().map(|(tick, h)| (*tick, h[0])).collect();
    // Shut until the switch, then opening: the switch (out of the door's touch) opened it.
    let opened_at = door
        .iter()
        .find(|(_, h)| *h > 0)
        .map(|(tick, _)| *tick)
        .expect("the door opened");
    let switch_tick = run
        .host_ticks()
        .iter()
        .position(|game| game.world.movers()[0].height > 0)
        .expect("the host's door opened") as u32;
    // The press is on emulator frames 240-243: the game's ticks from `start` on.
    let press = 240 - run.start;
    assert!(
        (press..=press + 8).contains(&switch_tick) && opened_at >= switch_tick,
        "the door opened at tick {switch_tick}, not on the switch's press (tick {press})"
    );
    // The switch shows its used texture from the press until the door is shut again.
    let thrown = |game: &Game| game.world.triggers()[0].thrown == TRIGGER_THROWN;
    let ticks = run.host_ticks();
    assert!(!ticks[..switch_tick as usize].iter().any(thrown));
    assert!(ticks[switch_tick as usize..]
        .iter()
        .take_while(|game| game.world.movers()[0].phase != Phase::Resting)
        .all(thrown));
    // It came down, then went back up, never below what the standing body needs (feet 0, eye
    // 32, headroom 16).
    let closing = door
        .windows(2)
        .position(|pair| pair[1].1 < pair[0].1)
        .expect("the door came down");
    let lowest = door[closing..]
        .windows(2)
        .find(|pair| pair[1].1 > pair[0].1)
        .map(|pair| pair[0].1);
    assert!(
        matches!(lowest, Some(h) if h >= 48),
        "the closing door did not turn back above the body: {door:?}"
    );
    assert!(door
        .iter()
        .all(|(tick, _)| *tick < 300 || door_height_ok(&run, *tick)));
}

#[test]
fn the_demo_through_the_door_and_on_the_lift_draws_the_host_s_frames() {
    // The demo (`cargo play`'s walk): every frame the ROM draws, its VRAM page identical to the
    // host's render of its logged pose and live world; among them frames with the door and the
    // lift mid-way and the body on the lift.
    let script = demo_script();
    let mut emulator = boot_until_playing();
    let mut renderer = Renderer::new();
    let keys: Vec<Keys> = (0..1150).map(|frame| script.keys_at(frame)).collect();
    let lift = sector_index("bench.map", "lift");
    let (mut compared, mut door_moving, mut lift_moving, mut on_lift) = (0, 0, 0, 0);
    play_frames(
        &mut emulator,
        &keys,
        |emulator, (player, world), render_line| {
            host_frame_matching(emulator, &mut renderer, (player, world), render_line);
            compared += 1;
            let heights = &world.expect("the bench map logs its world").heights;
            door_moving += usize::from(0 < heights[0] && heights[0] < 96);
            lift_moving += usize::from(0 < heights[1] && heights[1] < 128);
            on_lift += usize::from(player.sector == lift);
        },
    );
    assert!(compared > 500, "{compared} frames compared");
    assert!(
        door_moving > 5 && lift_moving > 20 && on_lift > 100,
        "door mid-way in {door_moving} frames, lift in {lift_moving}, the body on it in {on_lift}"
    );
}

/// Through the Start menu to the slopes map (two maps on from the bench map: the cursor starts
/// on the resolution, the map is two entries down), then east from the hall up the ramp onto
/// the landing and on across the bridge's deck over the canyon to the east ledge; a right-angle
/// turn south down the stairs to the bottom step, west into the tunnel, north along the
/// canyon's floor through the pit, under the bridge and into the pit beyond; fly mode on, up
/// through the pit's open ceiling into the air over it, and off: a fall back down through the
/// air's open floor onto the pit's.
const SLOPES_WALK: &str = "
10-12: START
20-22: DOWN
30-32: DOWN
40-42: RIGHT
50-52: RIGHT
60-62: START
80-340: UP
350-385: RIGHT
390-520: UP
530-565: RIGHT
570-618: UP
630-665: RIGHT
670-840: UP
850-852: SELECT
860-940: A
950-952: SELECT
";

/// Emulator frames [`SLOPES_WALK`] is played for.
const SLOPES_WALK_FRAMES: u32 = 1040;

#[test]
fn a_walk_up_the_ramp_over_the_bridge_and_under_it_is_the_host_s_every_tick() {
    let run = play(SLOPES_WALK, SLOPES_WALK_FRAMES);
    let name = |name: &str| sector_index("slopes.map", name);
    let (hall, ramp, landing, deck) = (name("hall"), name("ramp"), name("landing"), name("deck"));
    let (east_ledge, step8, tunnel) = (name("east_ledge"), name("step8"), name("tunnel"));
    let (south_pit, walkway) = (name("south_pit"), name("walkway"));
    let (north_pit, north_air) = (name("north_pit"), name("north_air"));
    // The host's ticks (every one the ROM's, `play`): on the slopes map, up the ramp (the feet
    // rising all the way), over the deck at the ledges' height, down the stairs, along the
    // canyon's floor under the deck, up through the open ceiling and back down.
    let mut visited: Vec<u16> = Vec::new();
    let mut feet_on_ramp = Vec::new();
    let mut under_the_deck = 0;
    for game in run.host_ticks() {
        if game.map().name != "slopes" {
            continue;
        }
        let player = &game.player;
        if !player.fly && player.sector != north_air && player.sector != north_pit {
            assert!(player.on_ground, "tick on the slopes map off the ground");
        }
        if visited.last() != Some(&player.sector) {
            visited.push(player.sector);
        }
        if player.sector == ramp {
            feet_on_ramp.push(player.feet_z.to_bits());
        }
        if player.sector == deck {
            assert_eq!(player.feet_z.to_bits(), 64 * 256, "the deck holds the body");
        }
        under_the_deck += usize::from(player.sector == walkway);
    }
    let steps: Vec<u16> = (1..=8).map(|k| name(&format!("step{k}"))).collect();
    let mut expected = vec![hall, ramp, landing, deck, east_ledge];
    expected.extend(&steps);
    expected.extend([tunnel, south_pit, walkway, north_pit, north_air, north_pit]);
    assert_eq!(visited, expected, "{visited:?}");
    assert_eq!(*steps.last().unwrap(), step8);
    assert!(
        feet_on_ramp.len() > 20,
        "{} ticks on the ramp",
        feet_on_ramp.len()
    );
    assert!(
        feet_on_ramp.windows(2).all(|pair| pair[0] <= pair[1]),
        "the feet rise all the way up the ramp"
    );
    assert!(under_the_deck > 10, "{under_the_deck} ticks under the deck");
    // The fall ends on the pit's floor.
    let last = run.last();
    assert_eq!(last.sector, north_pit, "{}", last.text);
    assert_eq!(
        run.host_ticks().last().unwrap().player.feet_z.to_bits(),
        -64 * 256
    );
}

#[test]
fn the_walk_up_the_ramp_and_through_the_canyon_draws_the_host_s_frames() {
    // Every frame the ROM draws on the way, its VRAM page identical to the host's render of its
    // logged pose: sloped walls, the ramp's and the bank's sloped floors, the canyon seen down
    // through the air's open floor from the deck, and up through the pits' open ceilings from
    // their floors.
    let script = KeyScript::parse(SLOPES_WALK).unwrap_or_else(|error| panic!("{error}"));
    let mut emulator = boot_until_playing();
    let mut renderer = Renderer::new();
    let keys: Vec<Keys> = (0..SLOPES_WALK_FRAMES)
        .map(|frame| script.keys_at(frame))
        .collect();
    let ramp = sector_index("slopes.map", "ramp");
    let pits = [
        sector_index("slopes.map", "north_pit"),
        sector_index("slopes.map", "south_pit"),
    ];
    let air = sector_index("slopes.map", "north_air");
    let (mut compared, mut on_ramp, mut in_pits, mut in_air) = (0, 0, 0, 0);
    play_frames(
        &mut emulator,
        &keys,
        |emulator, (player, world), render_line| {
            if field(render_line, "map") != Some("slopes") {
                return;
            }
            host_frame_matching(emulator, &mut renderer, (player, world), render_line);
            compared += 1;
            on_ramp += usize::from(player.sector == ramp);
            in_pits += usize::from(pits.contains(&player.sector));
            in_air += usize::from(player.sector == air);
        },
    );
    assert!(
        compared > 600 && on_ramp > 15 && in_pits > 100 && in_air > 10,
        "{compared} frames compared, {on_ramp} on the ramp, {in_pits} with the eye in a pit, {in_air} in the air over it"
    );
}
