//! Scripted demos: harness key scripts (one line per held range of emulator frames) that the
//! emulator tests play through the ROM, and the host replay of the same script through the
//! same game code.
//!
//! The ROM samples the buttons at every VBlank; the sample taken at VBlank `k` (counted from
//! power-on, 0-based) holds the keys of emulator frame `k + 1` (the interrupt runs at the start
//! of the frame after the one whose end raised it). The game starts at VBlank `s` (the ROM
//! logs `play start vblank=s`), so its tick `j` (1-based) ran on frame `s + j`.

use super::{field, number};
use portalcast::player::input::Buttons;
use portalcast_harness::KeyScript;
use portalcast_rom::game::Game;

/// Emulator frame of the game's tick `tick` (1-based), for a game that started at `start`.
pub fn frame_of_tick(start: u32, tick: u32) -> u32 {
    start + tick
}

/// The game after every tick of `script`: element `j` is the state after `j` ticks.
pub fn replay(script: &KeyScript, start: u32, ticks: u32) -> Vec<Game<'static>> {
    let mut game = Game::new(portalcast_rom::assets::MAPS);
    let mut states = vec![game];
    for tick in 1..=ticks {
        game.tick(Buttons(script.keys_at(frame_of_tick(start, tick)).bits()));
        states.push(game);
    }
    states
}

/// A signed `key=value` field of a ROM line.
pub fn signed(line: &str, key: &str) -> i64 {
    let text = field(line, key).unwrap_or_else(|| panic!("no {key}= in {line:?}"));
    text.parse()
        .unwrap_or_else(|_| panic!("{key}={text} is not a number in {line:?}"))
}

/// The ROM's `player …` line: the pose and state after the frame's ticks.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PlayerLine {
    /// Frame number (as in the `render` line that follows).
    pub frame: u32,
    /// Ticks run so far.
    pub tick: u32,
    /// Samples lost to a full ring (the game skipped those ticks).
    pub lost: u32,
    /// Eye x, y, z in 24.8 bits.
    pub x: i32,
    /// See `x`.
    pub y: i32,
    /// See `x`.
    pub z: i32,
    /// View angle, binary.
    pub angle: u16,
    /// The tracked sector.
    pub sector: u16,
    /// Horizon shift.
    pub look: i32,
    /// On the ground, crouched, flying, running.
    pub ground: bool,
    /// See `ground`.
    pub crouch: bool,
    /// See `ground`.
    pub fly: bool,
    /// See `ground`.
    pub run: bool,
    /// Menu cursor, or −1 when closed.
    pub menu: i32,
    /// The heads-up display is shown.
    pub hud: bool,
    /// The line itself.
    pub text: String,
}

impl PlayerLine {
    /// Parses a `player …` line.
    pub fn parse(text: &str) -> PlayerLine {
        let flag = |key: &str| number(text, key) != 0;
        PlayerLine {
            frame: number(text, "frame") as u32,
            tick: number(text, "tick") as u32,
            lost: number(text, "lost") as u32,
            x: signed(text, "x") as i32,
            y: signed(text, "y") as i32,
            z: signed(text, "z") as i32,
            angle: number(text, "angle") as u16,
            sector: number(text, "sector") as u16,
            look: signed(text, "look") as i32,
            ground: flag("ground"),
            crouch: flag("crouch"),
            fly: flag("fly"),
            run: flag("run"),
            menu: signed(text, "menu") as i32,
            hud: flag("hud"),
            text: text.to_owned(),
        }
    }

    /// The renderer's camera at this pose.
    pub fn camera(&self) -> portalcast::render::view::Camera {
        use portalcast::math::{Angle, Fx24_8, WorldPoint};
        portalcast::render::view::Camera {
            position: WorldPoint::new(Fx24_8::from_bits(self.x), Fx24_8::from_bits(self.y)),
            eye_z: Fx24_8::from_bits(self.z),
            angle: Angle::from_bits(self.angle),
            sector: self.sector,
            look_lines: self.look,
        }
    }

    /// The same fields from a host game.
    pub fn of(game: &Game) -> PlayerLine {
        let camera = game.camera();
        PlayerLine {
            frame: 0,
            tick: game.ticks(),
            lost: 0,
            x: camera.position.x.to_bits(),
            y: camera.position.y.to_bits(),
            z: camera.eye_z.to_bits(),
            angle: camera.angle.to_bits(),
            sector: camera.sector,
            look: camera.look_lines,
            ground: game.player.on_ground,
            crouch: game.player.crouched(),
            fly: game.player.fly,
            run: game.controls.always_run,
            menu: if game.menu.open {
                game.menu.cursor as i32
            } else {
                -1
            },
            hud: game.hud,
            text: String::new(),
        }
    }

    /// Whether the pose and state (not the frame number or the text) are the same.
    pub fn same_state(&self, other: &PlayerLine) -> bool {
        PlayerLine {
            frame: 0,
            lost: 0,
            text: String::new(),
            ..self.clone()
        } == PlayerLine {
            frame: 0,
            lost: 0,
            text: String::new(),
            ..other.clone()
        }
    }
}

/// The map and settings a ROM's `render` line names.
pub fn render_line_settings(
    text: &str,
) -> (
    portalcast_format::MapTables<'static>,
    portalcast::render::view::Settings,
) {
    use portalcast_rom::demo;
    let map = demo::map_named(field(text, "map").unwrap()).expect("the ROM names a compiled map");
    (map, line_settings(text))
}

/// The settings a ROM's `render` or `bench` line names ([`portalcast_rom::bench::SettingsLabel`]).
pub fn line_settings(text: &str) -> portalcast::render::view::Settings {
    use portalcast::frame::Resolution;
    use portalcast::render::view::{
        Floors, Preprocessing, Settings, SlopeSteps, TexturePlacement, ThingsShown,
    };
    use portalcast_rom::demo::lighting_from_label;
    let label = |key| field(text, key).unwrap_or_else(|| panic!("no {key}= in {text}"));
    Settings {
        resolution: Resolution::from_label(label("res")).unwrap(),
        lighting: lighting_from_label(label("lighting")).unwrap(),
        textures: TexturePlacement::from_label(label("tex")).unwrap(),
        preprocessing: Preprocessing::from_label(label("prep")).unwrap(),
        floors: Floors::from_label(label("floors")).unwrap(),
        things: ThingsShown::from_label(label("things")).unwrap(),
        slope_steps: SlopeSteps::from_label(label("slp")).unwrap(),
    }
}

/// The ROM's `world …` lines of one frame, printed after its `player` line on a map with movers
/// or light effects, gathered ([`WorldLines`]): the live state the frame was drawn with.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WorldLine {
    /// Each mover's height, in the order of `MapTables::movers`.
    pub heights: Vec<i32>,
    /// Each trigger's switch thrown, in the order of `MapTables::triggers`.
    pub thrown: Vec<bool>,
    /// Each light effect's level, in the order of `MapTables::lights`.
    pub lights: Vec<u8>,
}

/// Gathers a frame's `world … part=P/N` lines into its [`WorldLine`].
#[derive(Clone, Debug, Default)]
pub struct WorldLines {
    gathered: WorldLine,
    next_part: u32,
}

impl WorldLines {
    /// Takes the next `world …` line (without or with its `world ` prefix): the frame's whole
    /// world once its last part is in. Panics on a part out of order.
    pub fn push(&mut self, text: &str) -> Option<WorldLine> {
        let (part, parts) = WorldLine::part(text);
        if part == 1 {
            *self = WorldLines::default();
        }
        assert_eq!(
            part,
            self.next_part.max(1),
            "world line parts out of order: {text:?}"
        );
        let piece = WorldLine::parse(text);
        self.gathered.heights.extend(piece.heights);
        self.gathered.thrown.extend(piece.thrown);
        self.gathered.lights.extend(piece.lights);
        self.next_part = part + 1;
        (part == parts).then(|| std::mem::take(&mut self.gathered))
    }
}

impl WorldLine {
    /// Parses a `world …` line: one part of the world (`part=P/N`; the whole of it without
    /// `part=`).
    pub fn parse(text: &str) -> WorldLine {
        fn list<T>(text: &str, key: &str, item: impl Fn(&str) -> T) -> Vec<T> {
            field(text, key)
                .unwrap_or_else(|| panic!("no {key}= in {text:?}"))
                .split(',')
                .filter(|item| !item.is_empty())
                .map(item)
                .collect()
        }
        WorldLine {
            heights: list(text, "heights", |h| h.parse().expect("a height")),
            thrown: list(text, "thrown", |t| t == "1"),
            lights: list(text, "lights", |l| l.parse().expect("a light level")),
        }
    }

    /// A line's `part=P/N` (1/1 without it).
    fn part(text: &str) -> (u32, u32) {
        field(text, "part").map_or((1, 1), |part| {
            let (p, n) = part
                .split_once('/')
                .unwrap_or_else(|| panic!("part=P/N in {text:?}"));
            (p.parse().expect("a part"), n.parse().expect("a count"))
        })
    }
    /// The line the ROM prints after drawing `game`'s frame: its world, the light effects at
    /// the levels the frame shows them with (`Game::show`).
    pub fn of(game: &Game) -> WorldLine {
        let mut shown = *game;
        shown.show();
        WorldLine {
            heights: shown.world.movers().iter().map(|m| m.height).collect(),
            thrown: shown
                .world
                .triggers()
                .iter()
                .map(|t| t.thrown == portalcast_format::TRIGGER_THROWN)
                .collect(),
            lights: shown.world.lights(&shown.map()).collect(),
        }
    }

    /// `map`'s world as the line gives it (the map as it starts where `line` is `None`: the
    /// ROM prints no world line for a map without movers or light effects).
    pub fn world_of(
        line: Option<&WorldLine>,
        map: &portalcast_format::MapTables,
    ) -> portalcast_rom::game::GameWorld {
        let mut world = portalcast_rom::game::GameWorld::start(map);
        if let Some(line) = line {
            assert_eq!(line.heights.len(), map.movers.len(), "{line:?}");
            assert_eq!(line.lights.len(), map.lights.len(), "{line:?}");
            world.set_heights(map, &line.heights);
            world.set_thrown(&line.thrown);
            world.set_lights(map, &line.lights);
        }
        world
    }
}
