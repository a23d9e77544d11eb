//! The benchmark scene, `assets/maps/bench.map`, built from convex polygons and written out
//! in the text map format.
//!
//! Sectors are given as clockwise polygons (y down). Portals are found, not declared: a wall
//! whose reverse is a wall of another sector becomes a portal. Before that, every map vertex
//! lying inside another sector's wall is inserted into it, so partly shared edges (T-junctions)
//! split into segments both sides agree on.

use std::collections::HashMap;
use std::fmt::Write as _;

type Point = (i32, i32);

/// How a sector looks: heights, flats, light and the textures of its own walls and of the step
/// strips seen from inside it.
#[derive(Clone, Copy)]
struct Look {
    floor: i32,
    ceil: i32,
    floor_tex: &'static str,
    /// `"sky"` for an open ceiling.
    ceil_tex: &'static str,
    light: u8,
    wall: &'static str,
    upper: &'static str,
    lower: &'static str,
}

impl Look {
    const fn with(self, floor: i32, ceil: i32, light: u8) -> Look {
        Look {
            floor,
            ceil,
            light,
            ..self
        }
    }
}

struct Area {
    name: String,
    look: Look,
    outline: Vec<Point>,
}

/// Clockwise (y down) axis-aligned rectangle.
fn rect(x0: i32, y0: i32, x1: i32, y1: i32) -> Vec<Point> {
    vec![(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
}

const HALL: Look = Look {
    floor: 0,
    ceil: 192,
    floor_tex: "tiles",
    ceil_tex: "ceiling",
    light: 160,
    wall: "brick",
    upper: "brick",
    lower: "step",
};
const YARD: Look = Look {
    floor: 0,
    ceil: 320,
    floor_tex: "grass",
    ceil_tex: "sky",
    light: 230,
    wall: "stone",
    upper: "stone",
    lower: "stone",
};
const CORRIDOR: Look = Look {
    floor: 0,
    ceil: 96,
    floor_tex: "stone",
    ceil_tex: "metal",
    light: 200,
    wall: "metal",
    upper: "metal",
    lower: "metal",
};
const STAIRS: Look = Look {
    floor: 0,
    ceil: 128,
    floor_tex: "stone",
    ceil_tex: "ceiling",
    light: 120,
    wall: "stone",
    upper: "stone",
    lower: "step",
};
const GALLERY: Look = Look {
    floor: 128,
    ceil: 240,
    floor_tex: "wood",
    ceil_tex: "ceiling",
    light: 90,
    wall: "wood",
    upper: "trim",
    lower: "wood",
};
const WINDOW: Look = Look {
    floor: 160,
    ceil: 224,
    floor_tex: "trim",
    ceil_tex: "trim",
    light: 170,
    wall: "trim",
    upper: "trim",
    lower: "trim",
};
const SHRINE: Look = Look {
    floor: 16,
    ceil: 192,
    floor_tex: "marble",
    ceil_tex: "ceiling",
    light: 40,
    wall: "marble",
    upper: "marble",
    lower: "marble",
};

fn areas() -> Vec<Area> {
    let mut areas = Vec::new();
    let mut add = |name: &str, look: Look, outline: Vec<Point>| {
        areas.push(Area {
            name: name.to_string(),
            look,
            outline,
        })
    };

    // The great hall: 768×768 with chamfered corners, split 3×3 around a raised dais.
    add(
        "hall_nw",
        HALL,
        vec![(0, 128), (128, 0), (256, 0), (256, 256), (0, 256)],
    );
    add("hall_n", HALL, rect(256, 0, 512, 256));
    add(
        "hall_ne",
        HALL,
        vec![(512, 0), (640, 0), (768, 128), (768, 256), (512, 256)],
    );
    add("hall_w", HALL, rect(0, 256, 256, 512));
    add("dais", HALL.with(16, 192, 255), rect(256, 256, 512, 512));
    add("hall_e", HALL, rect(512, 256, 768, 512));
    add(
        "hall_sw",
        HALL,
        vec![(0, 512), (256, 512), (256, 768), (128, 768), (0, 640)],
    );
    add("hall_s", HALL, rect(256, 512, 512, 768));
    add(
        "hall_se",
        HALL,
        vec![(512, 512), (768, 512), (768, 640), (640, 768), (512, 768)],
    );

    // South of the hall, for the player: a crawlway whose ceiling is 40 above its floor (the
    // eye needs 16 of headroom, so only a crouched player, eye 16, gets through) into a small
    // den, and a ledge alcove whose floor is 24 up: too tall to step onto (at most 16), low
    // enough to jump onto.
    add("crawl", CORRIDOR.with(0, 40, 90), rect(272, 768, 336, 960));
    add("den", SHRINE.with(0, 128, 70), rect(224, 960, 384, 1120));
    add("ledge", HALL.with(24, 192, 190), rect(432, 768, 496, 832));

    // A low passage north into the courtyard.
    add(
        "passage",
        CORRIDOR.with(0, 112, 120),
        rect(320, -128, 448, 0),
    );

    // The courtyard under the sky, 3×3 around a sunken pool, chamfered outer corners.
    add(
        "yard_nw",
        YARD,
        vec![(0, -576), (64, -640), (256, -640), (256, -448), (0, -448)],
    );
    add("yard_n", YARD, rect(256, -640, 512, -448));
    add(
        "yard_ne",
        YARD,
        vec![
            (512, -640),
            (704, -640),
            (768, -576),
            (768, -448),
            (512, -448),
        ],
    );
    add("yard_w", YARD, rect(0, -448, 256, -320));
    let pool = Look {
        floor_tex: "water",
        ..YARD.with(-16, 320, 200)
    };
    add("pool", pool, rect(256, -448, 512, -320));
    add("yard_e", YARD, rect(512, -448, 768, -320));
    add(
        "yard_sw",
        YARD,
        vec![(0, -320), (256, -320), (256, -128), (64, -128), (0, -192)],
    );
    add("yard_s", YARD, rect(256, -320, 512, -128));
    add(
        "yard_se",
        YARD,
        vec![
            (512, -320),
            (768, -320),
            (768, -192),
            (704, -128),
            (512, -128),
        ],
    );

    // A dark octagonal shrine north of the courtyard, through an antechamber.
    add(
        "antechamber",
        SHRINE.with(8, 112, 90),
        rect(320, -704, 448, -640),
    );
    add(
        "shrine",
        SHRINE,
        vec![
            (304, -1088),
            (464, -1088),
            (576, -976),
            (576, -816),
            (464, -704),
            (304, -704),
            (192, -816),
            (192, -976),
        ],
    );

    // Windows from the upper gallery onto the courtyard: sills above both floors, lintels
    // below both ceilings, so each shows an upper and a lower strip from either side.
    add("window_1", WINDOW, rect(768, -560, 800, -496));
    add("window_2", WINDOW, rect(768, -416, 800, -352));
    add("window_3", WINDOW, rect(768, -288, 800, -224));
    add("gallery", GALLERY, rect(800, -640, 928, 0));

    // The upper corridor back east to the top of the stairs, lit in bands.
    add(
        "upper_1",
        CORRIDOR.with(128, 224, 200),
        rect(928, -64, 1216, 0),
    );
    add(
        "upper_2",
        CORRIDOR.with(128, 224, 60),
        rect(1216, -64, 1504, 0),
    );
    add(
        "upper_3",
        CORRIDOR.with(128, 224, 200),
        rect(1504, -64, 1792, 0),
    );
    add(
        "landing_top",
        STAIRS.with(128, 256, 150),
        rect(1792, -64, 1920, 64),
    );

    // The staircase: eight steps of 16 up from the lower landing, each 32 deep.
    for k in 0..8 {
        let floor = 16 * (k + 1);
        add(
            &format!("step_{}", k + 1),
            STAIRS.with(floor, floor + 112, 110 + 10 * k as u8),
            rect(1792, 320 - 32 * (k + 1), 1920, 320 - 32 * k),
        );
    }
    add(
        "landing_low",
        STAIRS.with(0, 128, 100),
        rect(1792, 320, 1920, 448),
    );

    // The long corridor from the hall east to the lower landing, alternating light and dark,
    // behind a door 16 deep at its mouth (`MOVERS`).
    add(
        "corridor_door",
        CORRIDOR.with(0, 96, 200),
        rect(768, 352, 784, 416),
    );
    for (k, light) in [200, 50, 200, 50].into_iter().enumerate() {
        let x = 768 + 256 * k as i32;
        add(
            &format!("corridor_{}", k + 1),
            CORRIDOR.with(0, 96, light),
            rect(x.max(784), 352, x + 256, 416),
        );
    }

    // A lift beside the staircase, from the lower landing's floor up to the upper landing's
    // (`MOVERS`): drawn raised.
    add(
        "lift",
        STAIRS.with(128, 256, 140),
        rect(1920, -64, 2048, 448),
    );
    areas
}

/// The bench's movers (issue 18): (sector, its mover words, the lowest and highest floor and
/// ceiling it takes, for the strips the generator writes on the walls round it).
struct MoverSpec {
    sector: &'static str,
    words: &'static str,
    floor: (i32, i32),
    ceil: (i32, i32),
}

const MOVERS: &[MoverSpec] = &[
    // The corridor's door: opens when walked into or used (or from the switch beside it), and
    // closes after 2.5 s.
    MoverSpec {
        sector: "corridor_door",
        words: "door touch tag=1",
        floor: (0, 0),
        ceil: (0, 96),
    },
    // The lift: down to the lower landing on use, up again after 2 s.
    MoverSpec {
        sector: "lift",
        words: "lift=0",
        floor: (0, 128),
        ceil: (256, 256),
    },
];

/// Light effects (issue 18): (sector, the words on its line). The pool's water shimmers, the
/// shrine's candle breathes, the far corridor's lamp is failing, and the switch that opens the
/// corridor's door (tag 1) also dims the hall's east bay.
const LIGHTS: &[(&str, &str)] = &[
    ("hall_e", "switched=90 tag=1"),
    ("pool", "glow=150 period=180"),
    ("shrine", "glow=12 period=90"),
    ("corridor_3", "flicker=60 period=6"),
];

/// Switches (issue 18): (sector, the wall's start and end, the words on that solid wall).
const SWITCHES: &[(&str, Point, Point, &str)] =
    &[("hall_e", (768, 256), (768, 352), "switch=trim tag=1")];

/// A sector's lowest and highest floor and ceiling: its mover's range, or its own heights.
fn height_range(name: &str, look: &Look) -> ((i32, i32), (i32, i32)) {
    MOVERS.iter().find(|mover| mover.sector == name).map_or(
        ((look.floor, look.floor), (look.ceil, look.ceil)),
        |mover| (mover.floor, mover.ceil),
    )
}

/// Images drawn in portal openings (issue 17): (sector, neighbour, the words on that sector's
/// portal wall). Written on one side only: the neighbour's twin wall gets the same middle
/// (docs/MAP_FORMAT.md, "Middles").
const MIDDLES: &[(&str, &str, &str)] = &[
    // A raised portcullis's grate in the passage north from the hall: seen through, and the
    // player ducks under it (the passage is the only way to the courtyard).
    ("hall_n", "passage", "mid=grate"),
    // Leaded glass in the gallery's windows onto the courtyard, drawn at 50 %: it stops the
    // player too.
    ("gallery", "window_1", "mid=window translucent blocks"),
    ("gallery", "window_2", "mid=window translucent blocks"),
    ("gallery", "window_3", "mid=window translucent blocks"),
];

/// Whether `p` lies strictly inside segment `a b`.
fn strictly_inside(a: Point, b: Point, p: Point) -> bool {
    let cross =
        i64::from(b.0 - a.0) * i64::from(p.1 - a.1) - i64::from(b.1 - a.1) * i64::from(p.0 - a.0);
    let dot =
        i64::from(p.0 - a.0) * i64::from(b.0 - a.0) + i64::from(p.1 - a.1) * i64::from(b.1 - a.1);
    let length = i64::from(b.0 - a.0).pow(2) + i64::from(b.1 - a.1).pow(2);
    cross == 0 && dot > 0 && dot < length
}

/// Inserts into each outline every vertex of every area that lies inside one of its walls.
fn split_t_junctions(areas: &mut [Area]) {
    let all: Vec<Point> = areas.iter().flat_map(|a| a.outline.clone()).collect();
    for area in areas.iter_mut() {
        let mut split = Vec::new();
        for (i, &a) in area.outline.iter().enumerate() {
            let b = area.outline[(i + 1) % area.outline.len()];
            split.push(a);
            let mut inside: Vec<Point> = all
                .iter()
                .copied()
                .filter(|&p| strictly_inside(a, b, p))
                .collect();
            inside.sort_by_key(|&p| i64::from(p.0 - a.0).abs() + i64::from(p.1 - a.1).abs());
            inside.dedup();
            split.extend(inside);
        }
        area.outline = split;
    }
}

/// The bench map's text, plus (sectors, walls, portal sides) for the summary.
pub fn bench_map() -> (String, (usize, usize, usize)) {
    let mut areas = areas();
    split_t_junctions(&mut areas);

    let mut names: HashMap<Point, String> = HashMap::new();
    let mut order: Vec<Point> = Vec::new();
    for point in areas.iter().flat_map(|a| a.outline.iter()) {
        if !names.contains_key(point) {
            names.insert(*point, format!("v{}", order.len()));
            order.push(*point);
        }
    }
    let mut owner: HashMap<(Point, Point), usize> = HashMap::new();
    for (index, area) in areas.iter().enumerate() {
        for (i, &a) in area.outline.iter().enumerate() {
            owner.insert((a, area.outline[(i + 1) % area.outline.len()]), index);
        }
    }

    let mut text = String::new();
    let _ = writeln!(
        text,
        "# bench.map: the benchmark scene (about thesis scale: 30+ sectors).\n\
         # Generated by `cargo run -p portalcast-assets --bin gen-assets -- assets/`; edit the\n\
         # generator (crates/assets/src/bin/gen-assets/bench_map.rs) rather than this file.\n\
         #\n\
         # A great hall (3x3 sectors, chamfered corners, a raised dais) opens north through a low\n\
         # passage onto a courtyard under the sky (sunken pool), and east into a long corridor\n\
         # of light and dark bands. A grate hangs in the passage (seen through, passable). The\n\
         # corridor ends at a staircase of eight 16-unit steps up to an upper corridor and a dim\n\
         # gallery whose three leaded windows (translucent, closed) overlook the courtyard. North\n\
         # of the courtyard, an antechamber leads into a dark octagonal shrine. South of the\n\
         # hall, a crawlway (40 high: crouch) leads to a den, next to a ledge 24 up (jump).\n\
         # Movers: a door at the corridor's mouth (walk into it, use it, or the switch on the hall's wall\n\
         # north of it) and a lift beside the staircase, between the two landings' floors.\n\
         # Light effects: the pool glows, the shrine's candle breathes, a corridor lamp flickers,\n\
         # and the door's switch dims the hall's east bay.\n"
    );
    for point in &order {
        let _ = writeln!(text, "vertex {} {} {}", names[point], point.0, point.1);
    }
    let (mut walls, mut portals) = (0, 0);
    for area in &areas {
        let look = &area.look;
        let _ = write!(
            text,
            "\nsector {} floor={} ceil={} floor_tex={} ceil_tex={} light={}",
            area.name, look.floor, look.ceil, look.floor_tex, look.ceil_tex, look.light
        );
        for mover in MOVERS.iter().filter(|mover| mover.sector == area.name) {
            let _ = write!(text, " {}", mover.words);
        }
        for (_, words) in LIGHTS.iter().filter(|(sector, _)| *sector == area.name) {
            let _ = write!(text, " {words}");
        }
        let _ = writeln!(text);
        for (i, &a) in area.outline.iter().enumerate() {
            let b = area.outline[(i + 1) % area.outline.len()];
            walls += 1;
            let _ = write!(text, "  wall {} {}", names[&a], names[&b]);
            match owner.get(&(b, a)) {
                Some(&other) => {
                    portals += 1;
                    let there = &areas[other].look;
                    let _ = write!(text, " portal={}", areas[other].name);
                    let both_sky = look.ceil_tex == "sky" && there.ceil_tex == "sky";
                    // A strip shows if it does at some height a mover on either side takes.
                    let (floors, ceils) = height_range(&area.name, look);
                    let (there_floors, there_ceils) = height_range(&areas[other].name, there);
                    if there_ceils.0 < ceils.1 && !both_sky {
                        let _ = write!(text, " upper={}", look.upper);
                    }
                    if there_floors.1 > floors.0 {
                        let _ = write!(text, " lower={}", look.lower);
                    }
                    let neighbour = areas[other].name.as_str();
                    for (_, _, words) in MIDDLES
                        .iter()
                        .filter(|(from, to, _)| *from == area.name && *to == neighbour)
                    {
                        let _ = write!(text, " {words}");
                    }
                }
                None => {
                    let _ = write!(text, " tex={}", look.wall);
                    for (_, _, _, words) in SWITCHES.iter().filter(|(sector, from, to, _)| {
                        *sector == area.name && (*from, *to) == (a, b)
                    }) {
                        let _ = write!(text, " {words}");
                    }
                }
            }
            let _ = writeln!(text);
        }
    }
    let _ = writeln!(
        text,
        "\n# Start in the south of the hall, facing north toward the dais and the courtyard.\n\
         player 384.5 700.5 angle=270\n\n\
         thing torch 128.5 384.5\n\
         thing torch 640.5 384.5\n\
         thing torch 128.5 -384.5\n\
         thing torch 640.5 -384.5\n\
         thing torch 384.5 -896.5"
    );
    let _ = writeln!(text, "\n{HALL_THINGS}");
    (text, (areas.len(), walls, portals))
}

/// The great hall's furnishings, over twenty things in view from the start (issue 17: the
/// bench's things): solid pillars at the inner corners of the corner sectors, torches along the
/// walls, lamps hanging over the aisles, a statue seen from eight sides on the dais and four
/// flickering braziers round it. Each footprint lies inside its sector.
const HALL_THINGS: &str = "\
# The hall's furnishings: pillars, torches, hanging lamps (one translucent, by the grate), a
# statue (8 rotations) on the dais and four braziers (animated) round it.
thing pillar 176 176 solid
thing pillar 592 176 solid
thing pillar 176 592 solid
thing pillar 592 592 solid
thing torch 200 24
thing torch 280 24
thing torch 488 24
thing torch 568 24
thing torch 24 300
thing torch 24 460
thing torch 744 300
thing torch 744 460
thing torch 24 560
thing torch 744 560
thing lamp 320 128 hang
thing lamp 448 128 hang
thing lamp 128 320 hang
thing lamp 640 320 hang
thing lamp 320 600 hang
thing lamp 448 600 hang
thing lamp 384 200 hang translucent
thing lamp 384 560 hang
thing lamp 200 448 hang
thing lamp 568 448 hang
thing statue 384 384 angle=90 solid radius=16
thing flame 288 288 anim=6
thing flame 480 288 anim=7
thing flame 288 480 anim=8
thing flame 480 480 anim=5";
