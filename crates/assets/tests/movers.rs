//! Movers and triggers (issue 18): the mover words of a `sector` line (`door`, `lift=`,
//! `platform=`, `crusher=`, `touch`, `locked`, `speed=`, `wait=`, `tag=`) and the trigger words of
//! a `wall` line (`switch=TEX tag=N`, `trigger=N`) compile to the exact `Mover` and `Trigger`
//! records; the strips moving heights expose need their textures; the light effect words of a
//! `sector` line (`glow=`, `strobe=`, `flicker=`, `switched=`, `period=`) compile to the exact
//! `Light` records; and every error is reported once, at its word.

mod common;

use common::{pattern, valid_assets};
use portalcast_assets::{compile_dir, compile_map_str, Catalog, CompiledMap};
use portalcast_format::limits::{LIGHTS_MAX, MOVERS_MAX, TRIGGERS_MAX};
use portalcast_format::{
    Light, MapTables, Mover, Trigger, LIGHT_FLICKER, LIGHT_GLOW, LIGHT_STROBE, LIGHT_SWITCHED,
    MOVER_CRUSHER, MOVER_DOOR, MOVER_LIFT, MOVER_ON_TOUCH, MOVER_ON_USE, MOVER_PLATFORM,
    NO_TEXTURE, TRIGGER_LINE, TRIGGER_SWITCH, TRIGGER_THROWN, WALL_SWITCH,
};

/// Catalog indices (sorted names).
const BRICK: u16 = 0;
const USED: u16 = 3;

fn catalog() -> Catalog {
    Catalog::new(["brick", "door", "stone", "used"], ["lamp", "torch"], false)
        .with_sprite_size("torch", 16, 48)
        .with_sprite_size("lamp", 8, 16)
}

/// A plain room's heights and textures.
const ROOM: &str = "floor=0 ceil=96 floor_tex=stone ceil_tex=stone";

/// Three rooms in a row, each its own sector: `west` (x 0..128), `mid` (128..160) and `east`
/// (160..288), all 128 deep, joined by portals; the player in the west room. Each field is the
/// words written on one line, so a test changes only what it is about.
#[derive(Clone, Copy)]
struct Rooms<'a> {
    /// Line 9: after `sector west`.
    west: &'a str,
    /// Line 14: after `sector mid`.
    mid: &'a str,
    /// Line 19: after `sector east`.
    east: &'a str,
    /// Line 10: after the west room's solid `wall a b tex=brick`.
    west_wall: &'a str,
    /// Line 11: after the west room's `wall b c portal=mid`.
    west_side: &'a str,
    /// Line 15: after the middle room's solid `wall b e tex=brick`.
    mid_wall: &'a str,
    /// Line 16: after the middle room's `wall e f portal=east`.
    mid_east: &'a str,
    /// Line 18: after the middle room's `wall c b portal=west`.
    mid_west: &'a str,
    /// Line 23: after the east room's `wall f e portal=mid`.
    east_side: &'a str,
    /// Line 24 on: after `player 64 64`.
    tail: &'a str,
}

impl Default for Rooms<'_> {
    fn default() -> Self {
        Rooms {
            west: ROOM,
            mid: ROOM,
            east: ROOM,
            west_wall: "",
            west_side: "",
            mid_wall: "",
            mid_east: "",
            mid_west: "",
            east_side: "",
            tail: "",
        }
    }
}

impl Rooms<'_> {
    fn text(&self) -> String {
        format!(
            "vertex a 0 0\nvertex b 128 0\nvertex c 128 128\nvertex d 0 128\n\
             vertex e 160 0\nvertex f 160 128\nvertex g 288 0\nvertex h 288 128\n\
             sector west {}\n\
             wall a b tex=brick {}\nwall b c portal=mid {}\nwall c d tex=brick\nwall d a tex=brick\n\
             sector mid {}\n\
             wall b e tex=brick {}\nwall e f portal=east {}\nwall f c tex=brick\nwall c b portal=west {}\n\
             sector east {}\n\
             wall e g tex=brick\nwall g h tex=brick\nwall h f tex=brick\nwall f e portal=mid {}\n\
             player 64 64\n{}",
            self.west,
            self.west_wall,
            self.west_side,
            self.mid,
            self.mid_wall,
            self.mid_east,
            self.mid_west,
            self.east,
            self.east_side,
            self.tail
        )
    }

    fn compile(&self) -> CompiledMap {
        let text = self.text();
        compile_map_str("rooms.map", &text, &catalog())
            .unwrap_or_else(|e| panic!("{e}\n---\n{text}"))
    }

    /// The one error the map gives: its line, its column, and its message.
    fn only_error(&self) -> (u32, u32, String) {
        only_error(&self.text())
    }
}

fn only_error(text: &str) -> (u32, u32, String) {
    let errors = compile_map_str("rooms.map", text, &catalog()).expect_err("an error");
    assert_eq!(errors.0.len(), 1, "{errors}\n---\n{text}");
    let error = &errors.0[0];
    (error.loc.line, error.loc.col, error.message.clone())
}

/// Where `needle` starts on line `line` (1-based) of `text`: its line and 1-based column.
fn at(text: &str, line: u32, needle: &str) -> (u32, u32) {
    let found = text
        .lines()
        .nth(line as usize - 1)
        .and_then(|l| l.find(needle))
        .unwrap_or_else(|| panic!("{needle:?} on line {line} of\n{text}"));
    (line, found as u32 + 1)
}

/// Where the value of `key=` on line `line` starts (the column after the `=`).
fn value_of(text: &str, line: u32, key: &str) -> (u32, u32) {
    let (line, col) = at(text, line, &format!("{key}="));
    (line, col + key.len() as u32 + 1)
}

/// Asserts that `rooms` gives one error, at `(line, col)`, whose message contains `text`.
fn assert_error(rooms: Rooms<'_>, place: (u32, u32), text: &str) {
    let (line, col, message) = rooms.only_error();
    assert_eq!((line, col), place, "{message}\n---\n{}", rooms.text());
    assert!(message.contains(text), "{message:?} lacks {text:?}");
}

const DOOR_ROOMS: Rooms<'static> = Rooms {
    west: ROOM,
    mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone door",
    east: ROOM,
    west_wall: "",
    west_side: "upper=door",
    mid_wall: "",
    mid_east: "",
    mid_west: "",
    east_side: "upper=door",
    tail: "",
};

fn door(words: &str, west_wall: &str, east_side: &str) -> Vec<Mover> {
    let mid = format!("{ROOM} door {words}");
    let east_side = format!("upper=door {east_side}");
    Rooms {
        mid: &mid,
        west_wall,
        east_side: &east_side,
        ..DOOR_ROOMS
    }
    .compile()
    .movers
}

#[test]
fn a_door_is_drawn_open_and_starts_closed() {
    let map = DOOR_ROOMS.compile();
    assert_eq!(
        map.movers,
        [Mover {
            sector: 1,
            kind: MOVER_DOOR,
            flags: MOVER_ON_USE,
            low: 0,
            high: 96,
            speed: 2,
            wait: 150,
            tag: 0,
            start: 0,
        }]
    );
    assert!(map.triggers.is_empty());
    // The heights drawn stay in the sector table.
    assert_eq!((map.sectors[1].floor_z, map.sectors[1].ceil_z), (0, 96));
    // The walls into the door keep the door's face as their upper strip.
    let door_texture = 1;
    assert_eq!(map.walls[1].upper_texture, door_texture);
    assert_eq!(map.walls[11].upper_texture, door_texture);
}

#[test]
fn door_words_set_its_flags_speed_wait_and_tag() {
    let expected = |flags, speed, wait, tag| Mover {
        sector: 1,
        kind: MOVER_DOOR,
        flags,
        low: 0,
        high: 96,
        speed,
        wait,
        tag,
        start: 0,
    };
    assert_eq!(
        door("touch", "", ""),
        [expected(MOVER_ON_USE | MOVER_ON_TOUCH, 2, 150, 0)]
    );
    assert_eq!(
        door("speed=64 wait=0 tag=65535", "", ""),
        [expected(MOVER_ON_USE, 64, 0, 65535)]
    );
    // The words may come in any order, before or after the settings.
    assert_eq!(
        door("wait=65535 touch speed=1", "", ""),
        [expected(MOVER_ON_USE | MOVER_ON_TOUCH, 1, 65535, 0)]
    );
    assert_eq!(
        door("locked tag=7", "switch=used tag=7", ""),
        [expected(0, 2, 150, 7)]
    );
    // A sector may be named like a word.
    let map = Rooms {
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone door",
        ..DOOR_ROOMS
    }
    .text()
    .replace("sector mid ", "sector door ")
    .replace("portal=mid", "portal=door");
    let map = compile_map_str("rooms.map", &map, &catalog()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.movers.len(), 1);
}

#[test]
fn a_lift_is_drawn_raised_and_goes_down() {
    // The lift's floor is 48 up, the west room's 0, the east room's 48: lowered, the lift shows
    // a step up into the east room, so its side needs lower=; the west room sees the raised
    // lift's step (as drawn).
    let rooms = Rooms {
        west: "floor=0 ceil=160 floor_tex=stone ceil_tex=stone",
        mid: "floor=48 ceil=160 floor_tex=stone ceil_tex=stone lift=0",
        east: "floor=48 ceil=160 floor_tex=stone ceil_tex=stone",
        west_side: "lower=brick",
        mid_east: "lower=brick",
        ..Rooms::default()
    };
    let lift = Mover {
        sector: 1,
        kind: MOVER_LIFT,
        flags: MOVER_ON_USE,
        low: 0,
        high: 48,
        speed: 2,
        wait: 120,
        tag: 0,
        start: 48,
    };
    assert_eq!(rooms.compile().movers, [lift]);
    let mid =
        "floor=48 ceil=160 floor_tex=stone ceil_tex=stone lift=-32 locked tag=2 speed=3 wait=9";
    let map = Rooms {
        mid,
        // Lowered below the west room's floor, the lift shows a step on that side too.
        mid_west: "lower=brick",
        east_side: "trigger=2",
        ..rooms
    }
    .compile();
    assert_eq!(
        map.movers,
        [Mover {
            flags: 0,
            low: -32,
            tag: 2,
            speed: 3,
            wait: 9,
            ..lift
        }]
    );
    // The lowered lift's lower strip, on its own side.
    assert_eq!(map.walls[5].lower_texture, BRICK);
}

#[test]
fn a_platform_moves_its_floor_for_ever() {
    let rooms = Rooms {
        west: "floor=0 ceil=128 floor_tex=stone ceil_tex=stone",
        mid: "floor=0 ceil=128 floor_tex=stone ceil_tex=stone platform=64",
        east: "floor=0 ceil=128 floor_tex=stone ceil_tex=stone",
        west_side: "lower=brick",
        east_side: "lower=brick",
        ..Rooms::default()
    };
    let platform = Mover {
        sector: 1,
        kind: MOVER_PLATFORM,
        flags: 0,
        low: 0,
        high: 64,
        speed: 1,
        wait: 60,
        tag: 0,
        start: 0,
    };
    assert_eq!(rooms.compile().movers, [platform]);
    // Below the floor drawn: it starts at the top, the floor drawn.
    let map = Rooms {
        mid: "floor=0 ceil=128 floor_tex=stone ceil_tex=stone platform=-40 speed=8 wait=1 tag=4",
        west_side: "",
        east_side: "",
        mid_east: "lower=brick",
        mid_west: "lower=brick",
        ..rooms
    }
    .compile();
    assert_eq!(
        map.movers,
        [Mover {
            low: -40,
            high: 0,
            speed: 8,
            wait: 1,
            tag: 4,
            ..platform
        }]
    );
}

#[test]
fn a_crusher_moves_its_ceiling_for_ever() {
    let map = Rooms {
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone crusher=24",
        west_side: "upper=brick",
        east_side: "upper=brick",
        ..Rooms::default()
    }
    .compile();
    assert_eq!(
        map.movers,
        [Mover {
            sector: 1,
            kind: MOVER_CRUSHER,
            flags: 0,
            low: 24,
            high: 96,
            speed: 1,
            wait: 30,
            tag: 0,
            start: 96,
        }]
    );
}

#[test]
fn switches_and_lines_compile_to_triggers_in_wall_order() {
    let map = Rooms {
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone door locked tag=3",
        west_wall: "switch=used tag=3",
        west_side: "upper=door trigger=3",
        mid_wall: "switch=brick tag=3",
        east_side: "upper=door trigger=3",
        ..Rooms::default()
    }
    .compile();
    assert_eq!(
        map.triggers,
        [
            Trigger {
                wall: 0,
                tag: 3,
                kind: TRIGGER_SWITCH,
                thrown: 0,
                used_texture: USED,
            },
            Trigger {
                wall: 1,
                tag: 3,
                kind: TRIGGER_LINE,
                thrown: 0,
                used_texture: NO_TEXTURE,
            },
            Trigger {
                wall: 4,
                tag: 3,
                kind: TRIGGER_SWITCH,
                thrown: 0,
                used_texture: BRICK,
            },
            Trigger {
                wall: 11,
                tag: 3,
                kind: TRIGGER_LINE,
                thrown: 0,
                used_texture: NO_TEXTURE,
            },
        ]
    );
    // The switch's wall keeps its own texture until used, and says it is a switch; the line
    // is the wall written.
    assert_eq!(map.walls[0].texture, BRICK);
    assert_eq!(map.walls[1].portal, 1);
    assert_eq!(map.walls[11].portal, 1);
    let switches: Vec<usize> = (0..map.walls.len())
        .filter(|&i| map.walls[i].flags & WALL_SWITCH != 0)
        .collect();
    assert_eq!(switches, [0, 4]);
    let tables = map.tables();
    assert_eq!(tables.solid_texture(0, &map.walls[0]), BRICK);
    let mut live = map.triggers.clone();
    live[0].thrown = TRIGGER_THROWN;
    let thrown = MapTables {
        triggers: &live,
        ..tables
    };
    assert_eq!(thrown.solid_texture(0, &map.walls[0]), USED);
    assert_eq!(thrown.solid_texture(4, &map.walls[4]), BRICK);
}

#[test]
fn a_trigger_names_its_wall_as_stored_clockwise() {
    // The east room listed counter-clockwise: stored reversed, so its last line (wall g e, the
    // switch, wall 11 in file order) is its first wall in the table (8), from e to g.
    let text = Rooms {
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone door tag=1",
        west_side: "upper=door",
        east_side: "upper=door",
        ..Rooms::default()
    }
    .text()
    .replace(
        "wall e g tex=brick\nwall g h tex=brick\nwall h f tex=brick\nwall f e portal=mid upper=door\n",
        "wall e f portal=mid upper=door\nwall f h tex=brick\nwall h g tex=brick\nwall g e tex=brick switch=used tag=1\n",
    );
    let map = compile_map_str("rooms.map", &text, &catalog()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.triggers.len(), 1);
    let wall = map.walls[usize::from(map.triggers[0].wall)];
    let (start, end) = (
        map.vertices[usize::from(wall.start)],
        map.vertices[usize::from(wall.end)],
    );
    assert_eq!(((start.x, start.y), (end.x, end.y)), ((160, 0), (288, 0)));
    assert_eq!(map.triggers[0].wall, 8);
}

#[test]
fn movers_are_listed_in_sector_order() {
    let map = Rooms {
        west: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone crusher=80",
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone",
        east: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone platform=8",
        mid_west: "upper=brick",
        mid_east: "lower=brick",
        tail: "",
        ..Rooms::default()
    }
    .text()
    .replace("player 64 64", "player 144 64");
    let map = compile_map_str("rooms.map", &map, &catalog()).unwrap_or_else(|e| panic!("{e}"));
    let kinds: Vec<(u16, u8)> = map.movers.iter().map(|m| (m.sector, m.kind)).collect();
    assert_eq!(kinds, [(0, MOVER_CRUSHER), (2, MOVER_PLATFORM)]);
}

#[test]
fn mover_words_in_the_wrong_place_are_refused_at_the_word() {
    let line = |mid: &str| {
        let mid = format!("{ROOM} {mid}");
        let rooms = Rooms {
            mid: &mid,
            west_side: "upper=brick lower=brick",
            east_side: "upper=brick lower=brick",
            mid_west: "upper=brick lower=brick",
            mid_east: "upper=brick lower=brick",
            ..Rooms::default()
        };
        (rooms.text(), rooms.only_error())
    };
    let cases: [(&str, &str, bool, &str); 14] = [
        (
            "door lift=-16",
            "lift=",
            true,
            "'lift=' after 'door': a sector moves one way",
        ),
        (
            "crusher=40 door",
            "door",
            false,
            "'door' after 'crusher=': a sector moves one way",
        ),
        (
            "speed=4",
            "speed=",
            true,
            "speed= applies to a moving sector; add a mover word",
        ),
        ("wait=4", "wait=", true, "wait= applies to a moving sector"),
        ("tag=4", "tag=", true, "tag= applies to a moving sector"),
        ("touch", "touch", false, "'touch' applies to a door"),
        (
            "locked",
            "locked",
            false,
            "'locked' applies to a door or a lift",
        ),
        (
            "lift=-8 touch",
            "touch",
            false,
            "'touch' applies to doors only, and this sector is a lift",
        ),
        (
            "platform=8 locked tag=1",
            "locked",
            false,
            "'locked' applies to doors and lifts only",
        ),
        ("door locked", "locked", false, "a locked door needs tag=N"),
        ("door touch locked tag=2", "touch", false, "keep one"),
        (
            "door speed=0",
            "speed=",
            true,
            "speed 0 is out of range; use 1..=64",
        ),
        (
            "door wait=65536",
            "wait=",
            true,
            "wait 65536 is out of range; use 0..=65535",
        ),
        (
            "door tag=0",
            "tag=",
            true,
            "tag 0 is out of range; use 1..=65535",
        ),
    ];
    for (words, word, is_setting, expected) in cases {
        let (text, (l, c, message)) = line(words);
        let place = if is_setting {
            value_of(&text, 14, word.trim_end_matches('='))
        } else {
            at(&text, 14, &format!(" {word}"))
        };
        let place = if is_setting {
            place
        } else {
            (place.0, place.1 + 1)
        };
        assert_eq!((l, c), place, "{words}: {message}");
        assert!(message.contains(expected), "{words}: {message:?}");
    }
    // Too fast.
    let (text, (l, c, message)) = line("door speed=65");
    assert_eq!((l, c), value_of(&text, 14, "speed"));
    assert!(message.contains("speed 65 is out of range"), "{message}");
}

#[test]
fn mover_heights_are_checked_against_the_sector() {
    let cases = [
        (
            "floor=16 ceil=96",
            "lift=16",
            "lift=16 is not below the sector's floor (16)",
        ),
        (
            "floor=0 ceil=96",
            "lift=-8193",
            "lift height -8193 is outside the limits",
        ),
        (
            "floor=0 ceil=96",
            "platform=0",
            "platform=0 is the sector's own floor",
        ),
        (
            "floor=0 ceil=96",
            "platform=96",
            "platform=96 is not below the sector's ceiling (96)",
        ),
        (
            "floor=0 ceil=96",
            "platform=8193",
            "platform height 8193 is outside the limits",
        ),
        (
            "floor=0 ceil=96",
            "crusher=0",
            "crusher=0 is not between the sector's floor (0) and ceiling (96)",
        ),
        ("floor=0 ceil=96", "crusher=96", "crusher=96 is not between"),
    ];
    for (heights, word, expected) in cases {
        let mid = format!("{heights} floor_tex=stone ceil_tex=stone {word}");
        let rooms = Rooms {
            mid: &mid,
            west_side: "upper=brick lower=brick",
            east_side: "upper=brick lower=brick",
            mid_west: "upper=brick lower=brick",
            mid_east: "upper=brick lower=brick",
            ..Rooms::default()
        };
        let key = word.split('=').next().unwrap_or_default();
        assert_error(rooms, value_of(&rooms.text(), 14, key), expected);
    }
}

#[test]
fn trigger_words_in_the_wrong_place_are_refused_at_the_word() {
    let door = "floor=0 ceil=96 floor_tex=stone ceil_tex=stone door tag=5";
    let base = Rooms {
        mid: door,
        west_side: "upper=door",
        east_side: "upper=door",
        ..Rooms::default()
    };
    let east_side_with = |words: &'static str| Rooms {
        east_side: words,
        ..base
    };
    let west_wall_with = |words: &'static str| Rooms {
        west_wall: words,
        ..base
    };
    let cases: [(Rooms<'_>, u32, &str, &str); 8] = [
        (
            east_side_with("upper=door switch=used tag=5"),
            23,
            "switch",
            "switch= goes on a solid wall",
        ),
        (
            west_wall_with("switch=used"),
            10,
            "switch",
            "switch= needs tag=N",
        ),
        (
            west_wall_with("tag=5"),
            10,
            "tag",
            "tag= on a wall goes with switch=TEX",
        ),
        (
            west_wall_with("trigger=5"),
            10,
            "trigger",
            "trigger= goes on a portal",
        ),
        (
            west_wall_with("switch=used tag=6"),
            10,
            "tag",
            "no mover or switched light has tag 6;",
        ),
        (
            east_side_with("upper=door trigger=9"),
            23,
            "trigger",
            "no mover or switched light has tag 9;",
        ),
        (
            west_wall_with("switch=lever tag=5"),
            10,
            "switch",
            "unknown texture 'lever'",
        ),
        (
            east_side_with("upper=door trigger=0"),
            23,
            "trigger",
            "trigger 0 is out of range; use 1..=65535",
        ),
    ];
    for (rooms, line, key, expected) in cases {
        assert_error(rooms, value_of(&rooms.text(), line, key), expected);
    }
    // Without any mover, a switch names a tag no mover has.
    let rooms = Rooms {
        west_wall: "switch=used tag=1",
        ..Rooms::default()
    };
    assert_error(
        rooms,
        value_of(&rooms.text(), 10, "tag"),
        "no mover or switched light has tag 1; give a moving sector",
    );
}

#[test]
fn strips_that_moving_heights_show_need_textures() {
    // A door: the walls into it, from both rooms.
    let rooms = Rooms {
        west_side: "",
        ..DOOR_ROOMS
    };
    assert_error(
        rooms,
        value_of(&rooms.text(), 11, "portal"),
        "portal to sector 'mid' needs upper=TEXTURE: it is a door whose ceiling comes down to 0 when it closes, lower than this sector's (96), so a strip of wall shows above the opening",
    );
    let rooms = Rooms {
        east_side: "",
        ..DOOR_ROOMS
    };
    assert_error(
        rooms,
        value_of(&rooms.text(), 23, "portal"),
        "portal to sector 'mid' needs upper=TEXTURE: it is a door",
    );
    // A lowered lift: the step up into the east room, on the lift's side.
    let lift = Rooms {
        west: "floor=0 ceil=160 floor_tex=stone ceil_tex=stone",
        mid: "floor=48 ceil=160 floor_tex=stone ceil_tex=stone lift=0",
        east: "floor=48 ceil=160 floor_tex=stone ceil_tex=stone",
        west_side: "lower=brick",
        ..Rooms::default()
    };
    assert_error(
        lift,
        value_of(&lift.text(), 16, "portal"),
        "portal to sector 'east' needs lower=TEXTURE: this sector is a lift whose floor goes down to 0, lower than the neighbour's (48), so a step shows below the opening",
    );
    // The raised lift from the west room is a step as drawn: the message of any step.
    let lift = Rooms {
        west_side: "",
        mid_east: "lower=brick",
        ..lift
    };
    assert_error(
        lift,
        value_of(&lift.text(), 11, "portal"),
        "portal to sector 'mid' needs lower=TEXTURE: its floor (48) is higher than this sector's (0)",
    );
    // A platform rising: the rooms' sides.
    let platform = Rooms {
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone platform=32",
        east_side: "lower=brick",
        ..Rooms::default()
    };
    assert_error(
        platform,
        value_of(&platform.text(), 11, "portal"),
        "portal to sector 'mid' needs lower=TEXTURE: it is a platform whose floor rises to 32, higher than this sector's (0)",
    );
    // A platform going down: its own sides.
    let platform = Rooms {
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone platform=-32",
        mid_west: "lower=brick",
        ..Rooms::default()
    };
    assert_error(
        platform,
        value_of(&platform.text(), 16, "portal"),
        "portal to sector 'east' needs lower=TEXTURE: this sector is a platform whose floor goes down to -32",
    );
    // A crusher: the rooms' sides.
    let crusher = Rooms {
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone crusher=40",
        west_side: "upper=brick",
        ..Rooms::default()
    };
    assert_error(
        crusher,
        value_of(&crusher.text(), 23, "portal"),
        "portal to sector 'mid' needs upper=TEXTURE: it is a crusher whose ceiling comes down to 40, lower than this sector's (96)",
    );
    // Two movers side by side: a lift (floor 48, down to 16) next to a platform (floor 0, up
    // to 32). Neither alone shows a step from the lift's side; together they do.
    let text = Rooms {
        west: "floor=48 ceil=160 floor_tex=stone ceil_tex=stone lift=16",
        mid: "floor=0 ceil=160 floor_tex=stone ceil_tex=stone platform=32",
        east: "floor=0 ceil=160 floor_tex=stone ceil_tex=stone",
        mid_west: "lower=brick",
        east_side: "lower=brick",
        ..Rooms::default()
    }
    .text()
    .replace("player 64 64", "player 224 64");
    let (line, col, message) = only_error(&text);
    assert_eq!((line, col), value_of(&text, 11, "portal"), "{message}");
    assert!(
        message.contains("needs lower=TEXTURE: it is a platform whose floor rises to 32 and this sector a lift whose floor goes down to 16"),
        "{message}"
    );
}

#[test]
fn both_sky_needs_no_upper_strip_even_for_a_door() {
    let map = Rooms {
        west: "floor=0 ceil=96 floor_tex=stone ceil_tex=sky",
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=sky door",
        ..Rooms {
            east_side: "upper=door",
            ..Rooms::default()
        }
    }
    .text();
    let catalog = Catalog::new(["brick", "door", "stone", "used"], ["torch"], true);
    let map = compile_map_str("rooms.map", &map, &catalog).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.walls[1].upper_texture, NO_TEXTURE);
}

#[test]
fn nothing_starts_or_stands_in_a_door_or_a_crusher() {
    for (mid, sides, what) in [
        (
            "door",
            "upper=door",
            "a door: it is closed when the map starts",
        ),
        (
            "crusher=48",
            "upper=brick",
            "a crusher: its ceiling keeps coming down",
        ),
    ] {
        let mid = format!("{ROOM} {mid}");
        let rooms = Rooms {
            mid: &mid,
            west_side: sides,
            east_side: sides,
            ..Rooms::default()
        };
        let player_inside = rooms.text().replace("player 64 64", "player 144 64");
        let (line, col, message) = only_error(&player_inside);
        assert_eq!((line, col), (24, 1), "{message}");
        assert!(
            message.contains(&format!(
                "player start at (144, 64) is in sector 'mid', {what}"
            )) && message.ends_with("start the player outside it"),
            "{message}"
        );
        let rooms = Rooms {
            tail: "thing lamp 32 32\nthing lamp 144 100\n",
            ..rooms
        };
        let (line, col, message) = rooms.only_error();
        assert_eq!((line, col), (26, 1), "{message}");
        assert!(
            message.contains(&format!(
                "thing 'lamp' at (144, 100) is in sector 'mid', {what}"
            )),
            "{message}"
        );
    }
}

#[test]
fn a_thing_on_a_platform_fits_under_the_ceiling_at_its_top() {
    // The platform rises from 0 to 64 under a ceiling at 96: 32 of room, the lamp is 16 tall.
    let rooms = |tail| Rooms {
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone platform=64",
        west_side: "lower=brick",
        east_side: "lower=brick",
        tail,
        ..Rooms::default()
    };
    let map = rooms("thing lamp 144 64 z=16\nthing lamp 144 32 hang z=16\n").compile();
    assert_eq!(map.things.len(), 2);
    let (line, col, message) = rooms("thing lamp 144 64 z=17\n").only_error();
    assert_eq!((line, col), (25, 1));
    assert_eq!(
        message,
        "thing 'lamp' at (144, 64): the sprite is 16 tall and stands 17 above the platform's floor at its highest (64), so its top (97) is 1 above the ceiling (96); lower z= by 1 (to 16)"
    );
    let (_, _, message) = rooms("thing lamp 144 64 hang z=17\n").only_error();
    assert!(
        message.contains("its bottom (63) is 1 below the platform's floor at its highest (64)"),
        "{message}"
    );
    // A lift's highest floor is the one drawn: the usual check.
    let lift = Rooms {
        west: "floor=0 ceil=160 floor_tex=stone ceil_tex=stone",
        mid: "floor=48 ceil=64 floor_tex=stone ceil_tex=stone lift=0",
        east: "floor=48 ceil=160 floor_tex=stone ceil_tex=stone",
        west_side: "lower=brick upper=brick",
        mid_east: "lower=brick",
        east_side: "upper=brick",
        tail: "thing lamp 144 64 z=1\n",
        ..Rooms::default()
    };
    let (_, _, message) = lift.only_error();
    assert!(
        message
            .contains("stands 1 above the floor (48), so its top (65) is 1 above the ceiling (64)"),
        "{message}"
    );
}

/// `count` boxes 64 wide in a row, 100 apart, each its own sector with solid walls: box `i`
/// gets the sector words `sector(i)` and on its first wall the words `first_wall(i)`. The
/// player stands in box 0.
fn boxes(count: usize, sector: impl Fn(usize) -> String, wall: impl Fn(usize) -> String) -> String {
    let mut text = String::new();
    for i in 0..count {
        let x = i * 100;
        text.push_str(&format!(
            "vertex a{i} {x} 0\nvertex b{i} {} 0\nvertex c{i} {} 64\nvertex d{i} {x} 64\n",
            x + 64,
            x + 64
        ));
    }
    for i in 0..count {
        text.push_str(&format!(
            "sector s{i} {ROOM} {}\nwall a{i} b{i} tex=brick {}\nwall b{i} c{i} tex=brick {}\nwall c{i} d{i} tex=brick {}\nwall d{i} a{i} tex=brick {}\n",
            sector(i),
            wall(i),
            wall(i),
            wall(i),
            wall(i)
        ));
    }
    text.push_str("player 32 32\n");
    text
}

#[test]
fn more_movers_than_a_map_holds_is_one_error_at_the_first_beyond() {
    let doors = |count: usize| {
        boxes(
            count + 1,
            |i| {
                if i == 0 {
                    String::new()
                } else {
                    "door".to_string()
                }
            },
            |_| String::new(),
        )
    };
    let map = compile_map_str("boxes.map", &doors(MOVERS_MAX as usize), &catalog())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.movers.len(), MOVERS_MAX as usize);
    let text = doors(MOVERS_MAX as usize + 2);
    let (line, col, message) = only_error(&text);
    // Box MOVERS_MAX + 1 (box 0 has none) holds the first beyond.
    let beyond = MOVERS_MAX as usize + 1;
    let sector_line = 4 * (MOVERS_MAX as usize + 3) + 5 * beyond + 1;
    assert_eq!((line, col), at(&text, sector_line as u32, "door"));
    assert_eq!(
        message,
        format!("the map has {} movers, more than the {MOVERS_MAX} a map may hold (this is the first beyond); remove some or split the map", MOVERS_MAX + 2)
    );
}

#[test]
fn more_triggers_than_a_map_holds_is_one_error_at_the_first_beyond() {
    // Box 0 is a door with tag 1 the switches all start; every wall of the others is a switch.
    let switches = |boxes_with_switches: usize| {
        boxes(
            boxes_with_switches + 1,
            |_| String::new(),
            |i| {
                if i == 0 {
                    String::new()
                } else {
                    "switch=used tag=1".to_string()
                }
            },
        )
        .replacen(
            "sector s0 floor=0 ceil=96 floor_tex=stone ceil_tex=stone ",
            "sector s0 floor=0 ceil=96 floor_tex=stone ceil_tex=stone lift=-8 tag=1",
            1,
        )
    };
    let per_box = 4;
    let full = TRIGGERS_MAX as usize / per_box;
    let map =
        compile_map_str("boxes.map", &switches(full), &catalog()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.triggers.len(), TRIGGERS_MAX as usize);
    assert!(map
        .triggers
        .iter()
        .all(|t| t.kind == TRIGGER_SWITCH && t.tag == 1));
    let text = switches(full + 1);
    let (line, col, message) = only_error(&text);
    // The first wall of box `full + 1` holds the first beyond.
    let wall_line = 4 * (full + 2) + 5 * (full + 1) + 2;
    assert_eq!((line, col), value_of(&text, wall_line as u32, "switch"));
    assert_eq!(
        message,
        format!("the map has {} switches and walk-over lines, more than the {TRIGGERS_MAX} a map may hold (this is the first beyond); remove some or split the map", TRIGGERS_MAX as usize + per_box)
    );
}

#[test]
fn an_asset_directory_compiles_a_switch_texture_used_nowhere_else() {
    let scratch = valid_assets("switch_texture", "stone");
    scratch.png("textures/lever.png", &pattern(16, 16));
    let map = Rooms {
        mid: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone door locked tag=1",
        west_side: "upper=brick",
        east_side: "upper=brick",
        west_wall: "switch=lever tag=1",
        tail: "thing torch 32 32\n",
        ..Rooms::default()
    }
    .text();
    scratch.write("maps/room.map", map.as_bytes());
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = compiled
        .textures()
        .iter()
        .map(|t| t.name.as_str())
        .collect();
    assert_eq!(names, ["brick", "lever", "stone"]);
    let map = &compiled.maps()[0];
    assert_eq!(map.triggers.len(), 1);
    let lever = &compiled.textures()[usize::from(map.triggers[0].used_texture)];
    assert_eq!(lever.name, "lever");
    assert!(
        !lever.columns.is_empty(),
        "a wall texture: its columns are compiled"
    );
    assert_eq!(map.movers[0].flags, 0);
}

/// A grid of three areas in a row, the middle cell a door (`door D ...`, with `words`).
fn door_grid(words: &str, row: &str) -> String {
    format!(
        "cell 64\nsolid # tex=brick\n\
         open . floor=0 ceil=128 floor_tex=stone ceil_tex=stone\n\
         door D on=. tex=door {words}\n\
         player @ on=. angle=0\n\
         grid\n#######\n{row}\n#######\n"
    )
}

#[test]
fn a_grid_door_cell_is_a_door_whose_face_is_its_texture() {
    let map = compile_map_str("doors.grid", &door_grid("", "#@.D..#"), &catalog())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.sectors.len(), 3);
    assert_eq!(
        map.movers,
        [Mover {
            sector: 1,
            kind: MOVER_DOOR,
            flags: MOVER_ON_USE,
            low: 0,
            high: 128,
            speed: 2,
            wait: 150,
            tag: 0,
            start: 0,
        }]
    );
    // The walls into the door show its face above the opening; its own walls show nothing.
    let door_texture = 1;
    for (index, wall) in map.walls.iter().enumerate() {
        let Some(next) = wall.neighbour() else {
            continue;
        };
        let into_door = next == 1;
        let expected = if into_door { door_texture } else { NO_TEXTURE };
        assert_eq!(wall.upper_texture, expected, "wall {index}");
        assert_eq!(wall.lower_texture, NO_TEXTURE, "wall {index}");
    }
    let map = compile_map_str(
        "doors.grid",
        &door_grid("touch speed=8 wait=60", "#@.D..#"),
        &catalog(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let door = map.movers[0];
    assert_eq!(
        (door.flags, door.speed, door.wait),
        (MOVER_ON_USE | MOVER_ON_TOUCH, 8, 60)
    );
    // Two door cells side by side are one door.
    let map = compile_map_str("doors.grid", &door_grid("", "#@DD..#"), &catalog())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.movers.len(), 1);
}

#[test]
fn grid_door_errors_are_located() {
    let error = |words: &str, row: &str| {
        let text = door_grid(words, row);
        (text.clone(), only_error_in("doors.grid", &text))
    };
    // The player on a door cell (`on=D`): at the cell.
    let text = door_grid("", "#.@...#").replace("on=. angle=0", "on=D angle=0");
    let (line, col, message) = only_error_in("doors.grid", &text);
    assert_eq!((line, col), (8, 3), "{message}");
    assert!(
        message.contains("player start at (160, 96) is in area 'D' at row 2, column 3, a door"),
        "{message}"
    );
    let (text, (line, col, message)) = error("speed=0", "#@.D..#");
    assert_eq!((line, col), value_of(&text, 4, "speed"));
    assert!(
        message.contains("speed 0 is out of range; use 1..=64"),
        "{message}"
    );
    let (text, (line, col, message)) = error("locked", "#@.D..#");
    assert_eq!((line, col), at(&text, 4, "locked"));
    assert!(
        message.contains("unknown word 'locked' for door"),
        "{message}"
    );
    let text = door_grid("", "#@.D..#").replace("door D on=. tex=door ", "door D on=x tex=door");
    let (line, col, message) = only_error_in("doors.grid", &text);
    assert_eq!((line, col), value_of(&text, 4, "on"));
    assert!(
        message.contains("on=x is not an open cell character"),
        "{message}"
    );
    let text = door_grid("", "#@.D..#").replace(" tex=door", "");
    let (line, col, message) = only_error_in("doors.grid", &text);
    assert_eq!((line, col), (4, 1));
    assert!(message.contains("door needs tex=TEXTURE"), "{message}");
}

fn only_error_in(file_name: &str, text: &str) -> (u32, u32, String) {
    let errors = compile_map_str(file_name, text, &catalog()).expect_err("an error");
    assert_eq!(errors.0.len(), 1, "{errors}\n---\n{text}");
    let error = &errors.0[0];
    (error.loc.line, error.loc.col, error.message.clone())
}

/// A room's heights and textures with its light at 200.
const LIT_ROOM: &str = "floor=0 ceil=96 floor_tex=stone ceil_tex=stone light=200";

/// A `Light` record, by its fields in order.
fn light(sector: u16, kind: u8, low: u8, period: u16, tag: u16) -> Light {
    Light {
        sector,
        kind,
        low,
        period,
        tag,
    }
}

/// The lights of the three rooms with `west`, `mid` and `east` written after [`LIT_ROOM`], the
/// middle room's portals given their strips (a door there needs them).
fn lights(west: &str, mid: &str, east: &str) -> Vec<Light> {
    let (west, mid, east) = (
        format!("{LIT_ROOM} {west}"),
        format!("{LIT_ROOM} {mid}"),
        format!("{LIT_ROOM} {east}"),
    );
    Rooms {
        west: &west,
        mid: &mid,
        east: &east,
        west_side: "upper=door",
        east_side: "upper=door",
        ..Rooms::default()
    }
    .compile()
    .lights
}

#[test]
fn each_light_effect_compiles_with_its_default_period() {
    assert_eq!(
        lights("glow=100", "strobe=20", "flicker=0"),
        [
            light(0, LIGHT_GLOW, 100, 120, 0),
            light(1, LIGHT_STROBE, 20, 40, 0),
            light(2, LIGHT_FLICKER, 0, 4, 0),
        ]
    );
    // A switched light has no period, and its tag; the word may come after tag=.
    assert_eq!(
        lights("", "tag=7 switched=199", ""),
        [light(1, LIGHT_SWITCHED, 199, 0, 7)]
    );
    // With the default light= (128), 127 is the highest low level.
    let rooms = Rooms {
        east: "floor=0 ceil=96 floor_tex=stone ceil_tex=stone glow=127",
        ..Rooms::default()
    };
    assert_eq!(rooms.compile().lights, [light(2, LIGHT_GLOW, 127, 120, 0)]);
}

#[test]
fn each_light_effect_takes_its_period() {
    assert_eq!(
        lights(
            "glow=0 period=2",
            "strobe=20 period=6",
            "flicker=50 period=65535"
        ),
        [
            light(0, LIGHT_GLOW, 0, 2, 0),
            light(1, LIGHT_STROBE, 20, 6, 0),
            light(2, LIGHT_FLICKER, 50, 65535, 0),
        ]
    );
    assert_eq!(
        lights("period=300 glow=10", "", "strobe=1 period=65535"),
        [
            light(0, LIGHT_GLOW, 10, 300, 0),
            light(2, LIGHT_STROBE, 1, 65535, 0),
        ]
    );
}

#[test]
fn a_door_and_a_switched_light_share_their_sector_and_its_tag() {
    let map = Rooms {
        mid: &format!("{LIT_ROOM} door tag=4 switched=50"),
        west_wall: "switch=used tag=4",
        west_side: "upper=door",
        east_side: "upper=door",
        ..Rooms::default()
    }
    .compile();
    assert_eq!(map.lights, [light(1, LIGHT_SWITCHED, 50, 0, 4)]);
    assert_eq!((map.movers[0].sector, map.movers[0].tag), (1, 4));
    assert_eq!(map.triggers[0].tag, 4);
    // A glowing door: tag= is the door's alone, the glow's record has none.
    let map = Rooms {
        mid: &format!("{LIT_ROOM} door glow=90 tag=4"),
        west_wall: "switch=used tag=4",
        west_side: "upper=door",
        east_side: "upper=door",
        ..Rooms::default()
    }
    .compile();
    assert_eq!(map.lights, [light(1, LIGHT_GLOW, 90, 120, 0)]);
    assert_eq!(map.movers[0].tag, 4);
}

#[test]
fn a_switch_or_a_line_may_name_a_switched_light_alone() {
    let map = Rooms {
        east: &format!("{LIT_ROOM} switched=10 tag=9"),
        west_wall: "switch=used tag=9",
        mid_east: "trigger=9",
        ..Rooms::default()
    }
    .compile();
    assert_eq!(map.lights, [light(2, LIGHT_SWITCHED, 10, 0, 9)]);
    assert!(map.movers.is_empty());
    let kinds: Vec<(u8, u16)> = map.triggers.iter().map(|t| (t.kind, t.tag)).collect();
    assert_eq!(kinds, [(TRIGGER_SWITCH, 9), (TRIGGER_LINE, 9)]);
}

#[test]
fn bad_light_effects_are_refused_at_the_word() {
    // (the middle room's words after its heights and textures, the key whose value the error
    // is at, what the message says)
    let cases: [(&str, &str, &str); 20] = [
        (
            "light=200 glow=10 strobe=20",
            "strobe",
            "'strobe=' after 'glow=': a sector has one light effect; keep one of",
        ),
        (
            "light=200 switched=5 tag=1 flicker=9",
            "flicker",
            "'flicker=' after 'switched=': a sector has one light effect",
        ),
        (
            "light=200 glow=200",
            "glow",
            "sector 'mid': glow=200 is not below the sector's light 200",
        ),
        (
            "flicker=128",
            "flicker",
            "sector 'mid': flicker=128 is not below the sector's light 128",
        ),
        (
            "light=200 glow=256",
            "glow",
            "glow low level 256 is out of range; use 0..=255",
        ),
        (
            "light=200 strobe=-1",
            "strobe",
            "strobe low level -1 is out of range; use 0..=255",
        ),
        (
            "light=200 flicker=dim",
            "flicker",
            "flicker low level 'dim' is not an integer",
        ),
        (
            "light=200 period=30",
            "period",
            "period= applies to a light effect; add glow=LOW, strobe=LOW or flicker=LOW, or remove period=",
        ),
        (
            "light=200 glow=10 period=1",
            "period",
            "glow period 1 is out of range; use 2..=65535",
        ),
        (
            "light=200 flicker=10 period=65536",
            "period",
            "flicker period 65536 is out of range; use 2..=65535",
        ),
        (
            "light=200 strobe=10 period=5",
            "period",
            "strobe period 5 is out of range; use 6..=65535 (a strobe is lit 5 ticks of each period, dark the rest)",
        ),
        (
            "light=200 strobe=10 period=fast",
            "period",
            "strobe period 'fast' is not an integer",
        ),
        (
            "light=200 switched=5 tag=2 period=10",
            "period",
            "period= applies to a glow, a strobe or a flicker: a switched light changes when",
        ),
        (
            "light=200 switched=5",
            "switched",
            "switched= needs tag=N on the same line",
        ),
        (
            "light=200 tag=3",
            "tag",
            "tag= applies to a moving sector or a switched light; add a mover word (door, lift=LOW, platform=OTHER, crusher=LOW) or switched=LOW, or remove tag=",
        ),
        (
            "light=200 glow=10 tag=3",
            "tag",
            "tag= applies to a moving sector or a switched light",
        ),
        // A bad switched= is one error: its tag= is not also refused for want of a light.
        (
            "light=200 switched=300 tag=2",
            "switched",
            "switched low level 300 is out of range",
        ),
        // A bad tag= is one error: the switched light is not also refused for want of a tag.
        (
            "light=200 switched=5 tag=0",
            "tag",
            "tag 0 is out of range; use 1..=65535",
        ),
        // A light effect is no mover: it does not make speed= right, nor a mover period=.
        (
            "light=200 glow=10 speed=2",
            "speed",
            "speed= applies to a moving sector",
        ),
        (
            "light=200 door period=20",
            "period",
            "period= applies to a light effect",
        ),
    ];
    for (words, key, message) in cases {
        let mid = format!("floor=0 ceil=96 floor_tex=stone ceil_tex=stone {words}");
        let rooms = Rooms {
            mid: &mid,
            west_side: "upper=door",
            east_side: "upper=door",
            ..Rooms::default()
        };
        let (line, col, found) = rooms.only_error();
        assert_eq!(
            (line, col),
            value_of(&rooms.text(), 14, key),
            "{words}: {found}"
        );
        assert!(
            found.contains(message),
            "{words}: {found:?} lacks {message:?}"
        );
    }
    // A switch or a line whose tag names no mover and no switched light (a glow's does not
    // count: only a switched light is turned by a tag).
    for (west_wall, mid_east, key) in [
        ("switch=used tag=8", "", "tag"),
        ("", "trigger=8", "trigger"),
    ] {
        let rooms = Rooms {
            mid: &format!("{LIT_ROOM} glow=10"),
            west_wall,
            mid_east,
            ..Rooms::default()
        };
        let line = if west_wall.is_empty() { 16 } else { 10 };
        assert_error(
            rooms,
            value_of(&rooms.text(), line, key),
            "no mover or switched light has tag 8; give a moving sector (door, lift=, platform=, crusher=) or a switched light (switched=LOW) tag=8, or use the tag of one",
        );
    }
}

/// `count` boxes 64 wide in rows of 20, 100 apart (so that `LIGHTS_MAX` of them stay within
/// the world's limits), each its own sector with solid walls, box `i` with the sector words
/// `sector(i)`; the player in box 0.
fn box_rows(count: usize, sector: impl Fn(usize) -> String) -> String {
    let mut text = String::new();
    for i in 0..count {
        let (x, y) = ((i % 20) * 100, (i / 20) * 100);
        text.push_str(&format!(
            "vertex a{i} {x} {y}\nvertex b{i} {} {y}\nvertex c{i} {} {}\nvertex d{i} {x} {}\n",
            x + 64,
            x + 64,
            y + 64,
            y + 64
        ));
    }
    for i in 0..count {
        text.push_str(&format!(
            "sector s{i} {ROOM} {}\nwall a{i} b{i} tex=brick\nwall b{i} c{i} tex=brick\nwall c{i} d{i} tex=brick\nwall d{i} a{i} tex=brick\n",
            sector(i)
        ));
    }
    text.push_str("player 32 32\n");
    text
}

#[test]
fn more_light_effects_than_a_map_holds_is_one_error_at_the_first_beyond() {
    // Box 0 keeps its light; every other box glows.
    let glows = |count: usize| {
        box_rows(count + 1, |i| {
            if i == 0 {
                String::new()
            } else {
                "glow=10".to_string()
            }
        })
    };
    let map = compile_map_str("boxes.map", &glows(LIGHTS_MAX as usize), &catalog())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.lights.len(), LIGHTS_MAX as usize);
    assert!(map
        .lights
        .iter()
        .enumerate()
        .all(|(i, l)| usize::from(l.sector) == i + 1));
    let text = glows(LIGHTS_MAX as usize + 2);
    let (line, col, message) = only_error(&text);
    // Box LIGHTS_MAX + 1 (box 0 has none) holds the first beyond.
    let beyond = format!("sector s{} ", LIGHTS_MAX + 1);
    let sector_line = text
        .lines()
        .position(|l| l.starts_with(&beyond))
        .expect("the box's sector line")
        + 1;
    assert_eq!((line, col), value_of(&text, sector_line as u32, "glow"));
    assert_eq!(
        message,
        format!("the map has {} light effects, more than the {LIGHTS_MAX} a map may hold (this is the first beyond); remove some or split the map", LIGHTS_MAX + 2)
    );
}
