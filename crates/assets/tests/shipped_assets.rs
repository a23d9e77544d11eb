//! The repository's own assets: they compile, the tables satisfy every invariant the engine
//! relies on, the bench map round-trips and meets its design goals, and the generator
//! reproduces the committed files.

mod common;

use std::collections::{BTreeMap, HashMap, VecDeque};

use common::{shipped_assets, Scratch};
use portalcast_assets::{compile_dir, Compiled};
use portalcast_format::{
    MapTables, Sector, NO_TEXTURE, SKY, THING_HANGING, THING_TRANSLUCENT, WALL_MIDDLE_BLOCKS,
    WALL_MIDDLE_TRANSLUCENT, WALL_SWITCH,
};

fn compiled() -> Compiled {
    compile_dir(&shipped_assets()).unwrap_or_else(|e| panic!("shipped assets must compile:\n{e}"))
}

fn point(map: &MapTables<'_>, vertex: u16) -> (i64, i64) {
    let v = map.vertices[usize::from(vertex)];
    (i64::from(v.x), i64::from(v.y))
}

fn cross(o: (i64, i64), a: (i64, i64), b: (i64, i64)) -> i64 {
    (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
}

/// Whether a 24.8 position is strictly inside a sector (right of every wall).
fn strictly_inside(map: &MapTables<'_>, sector: &Sector, x_fx8: i32, y_fx8: i32) -> bool {
    let p = (i64::from(x_fx8), i64::from(y_fx8));
    map.sector_walls(sector).iter().all(|w| {
        let (a, b) = (point(map, w.start), point(map, w.end));
        cross((a.0 * 256, a.1 * 256), (b.0 * 256, b.1 * 256), p) > 0
    })
}

fn check_invariants(map: &MapTables<'_>, texture_count: usize, compiled: &Compiled) {
    let name = map.name;
    let mut next_wall = 0;
    for (index, sector) in map.sectors.iter().enumerate() {
        assert_eq!(
            usize::from(sector.first_wall),
            next_wall,
            "{name}: sectors own consecutive walls"
        );
        next_wall += usize::from(sector.wall_count);
        assert!(sector.wall_count >= 3 && sector.floor_z < sector.ceil_z);
        assert!(usize::from(sector.floor_texture) < texture_count);
        assert!(sector.ceil_texture == SKY || usize::from(sector.ceil_texture) < texture_count);
        let walls = map.sector_walls(sector);
        let mut area = 0;
        for (i, wall) in walls.iter().enumerate() {
            // The compiler's twin table: each portal's twin is the wall of its sector that
            // leads back with the ends swapped (the search `MapTables::twin` makes without the
            // table), the twin's twin is the wall itself, and a solid wall has none.
            let wall_index = usize::from(sector.first_wall) + i;
            assert_eq!(
                map.wall_twins.len(),
                map.walls.len(),
                "{name}: a twin per wall"
            );
            let searched = MapTables {
                wall_twins: &[],
                ..*map
            }
            .twin(index as u16, wall_index);
            let twin = map.twin(index as u16, wall_index);
            assert_eq!(twin, searched, "{name}: wall {wall_index}'s twin");
            match (wall.neighbour(), twin) {
                (None, twin) => assert_eq!(twin, None, "{name}: a solid wall has no twin"),
                (Some(other), Some(twin)) => {
                    let back = &map.walls[twin];
                    assert_eq!(
                        (back.start, back.end, usize::from(back.portal)),
                        (wall.end, wall.start, index),
                        "{name}: wall {wall_index}'s twin leads back"
                    );
                    assert_eq!(
                        map.twin(other, twin),
                        Some(wall_index),
                        "{name}: twins pair"
                    );
                }
                (Some(_), None) => panic!("{name}: portal wall {wall_index} has no twin"),
            }
            let next = walls[(i + 1) % walls.len()];
            assert_eq!(wall.end, next.start, "{name}: sector {index} is closed");
            let (a, b, c) = (
                point(map, wall.start),
                point(map, wall.end),
                point(map, next.end),
            );
            assert_ne!(a, b, "{name}: no zero-length wall");
            assert!(
                cross(a, b, c) >= 0,
                "{name}: sector {index} is convex and clockwise"
            );
            area += a.0 * b.1 - b.0 * a.1;
            match wall.neighbour() {
                None => {
                    assert!(usize::from(wall.texture) < texture_count);
                    assert_eq!(
                        (wall.upper_texture, wall.lower_texture),
                        (NO_TEXTURE, NO_TEXTURE)
                    );
                    assert_eq!(
                        (wall.middle, wall.flags & !WALL_SWITCH),
                        (NO_TEXTURE, 0),
                        "{name}: no middle on a solid wall"
                    );
                }
                Some(other) => {
                    assert_eq!(wall.texture, NO_TEXTURE);
                    let there = &map.sectors[usize::from(other)];
                    let back = map
                        .sector_walls(there)
                        .iter()
                        .find(|w| w.start == wall.end && w.end == wall.start)
                        .unwrap_or_else(|| {
                            panic!("{name}: portal of sector {index} has a matching wall")
                        });
                    assert_eq!(
                        usize::from(back.portal),
                        index,
                        "{name}: portals point both ways"
                    );
                    assert_eq!(
                        (back.middle, back.flags),
                        (wall.middle, wall.flags),
                        "{name}: both sides of a portal share its middle"
                    );
                    if wall.middle == NO_TEXTURE {
                        assert_eq!(wall.flags, 0, "{name}: middle flags need a middle");
                    } else {
                        let set = &compiled.sprite_sets()[usize::from(wall.middle)];
                        assert_eq!(
                            (set.frames, set.rotations),
                            (1, 1),
                            "{name}: a still middle"
                        );
                    }
                    let both_sky = sector.ceil_texture == SKY && there.ceil_texture == SKY;
                    // The heights at both ends of the wall (a slope's there; a flat sector's
                    // everywhere): a strip shows where the neighbour's ceiling is lower, or its
                    // floor higher, at either end (the compiler's rule).
                    let ends = [wall.start, wall.end].map(|vertex| {
                        let v = map.vertices[usize::from(vertex)];
                        let at = |s| map.heights_fx8_at(s, v.x * 256, v.y * 256);
                        (at(sector), at(there))
                    });
                    if !both_sky && ends.iter().any(|((_, here), (_, other))| other < here) {
                        assert!(usize::from(wall.upper_texture) < texture_count);
                    }
                    if ends.iter().any(|((here, _), (other, _))| other > here) {
                        assert!(usize::from(wall.lower_texture) < texture_count);
                    }
                }
            }
        }
        assert!(area > 0, "{name}: sector {index} runs clockwise (y down)");
    }
    assert_eq!(next_wall, map.walls.len());
    let start = &map.sectors[usize::from(map.player_start.sector)];
    assert!(
        strictly_inside(map, start, map.player_start.x_fx8, map.player_start.y_fx8),
        "{name}: player inside"
    );
    for (index, thing) in map.things.iter().enumerate() {
        // A set's images are in the table, all of one size.
        let set = &compiled.sprite_sets()[usize::from(thing.sprite)];
        let first = usize::from(set.first);
        let images = &compiled.sprites()
            [first..first + usize::from(set.frames) * usize::from(set.rotations)];
        let sprite = &images[0];
        assert!(images
            .iter()
            .all(|i| (i.width, i.height) == (sprite.width, sprite.height)));
        assert!(thing.frame_ticks >= 1, "{name}: thing {index} frame ticks");
        let sector = &map.sectors[usize::from(thing.sector)];
        assert!(
            strictly_inside(map, sector, thing.x_fx8, thing.y_fx8),
            "{name}: thing inside"
        );
        assert!(
            map.things_in(thing.sector).contains(thing),
            "{name}: thing {index} listed with its sector"
        );
        // The renderer's promise (src/render/surface.rs): the footprint, a disc at least half
        // the sprite wide, lies inside the sector, and the sprite between floor and ceiling.
        let radius = i64::from(thing.radius);
        assert!(
            2 * radius >= i64::from(sprite.width),
            "{name}: thing {index} radius"
        );
        let p = (i64::from(thing.x_fx8), i64::from(thing.y_fx8));
        for wall in map.sector_walls(sector) {
            let (a, b) = (point(map, wall.start), point(map, wall.end));
            let depth = i128::from(cross((a.0 * 256, a.1 * 256), (b.0 * 256, b.1 * 256), p));
            let length_squared = i128::from((b.0 - a.0).pow(2) + (b.1 - a.1).pow(2));
            let reach = 65536 * i128::from(radius);
            assert!(
                depth * depth >= reach * reach * length_squared,
                "{name}: thing {index} footprint crosses a wall line"
            );
        }
        let (z, height) = (thing.z as i32, i32::from(sprite.height));
        let (bottom, top) = if thing.flags & THING_HANGING != 0 {
            (sector.ceil_z - z - height, sector.ceil_z - z)
        } else {
            (sector.floor_z + z, sector.floor_z + z + height)
        };
        assert!(
            bottom >= sector.floor_z && top <= sector.ceil_z,
            "{name}: thing {index} fits in height"
        );
    }
}

#[test]
fn shipped_maps_satisfy_the_table_invariants() {
    let compiled = compiled();
    let names: Vec<&str> = compiled.maps().iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["bench", "grid", "slopes", "tiny"]);
    for map in compiled.maps() {
        check_invariants(&map.tables(), compiled.textures().len(), &compiled);
    }
    assert_eq!(
        compiled.left_out(),
        [] as [String; 0],
        "every shipped asset is used"
    );
    let sets = compiled.sprite_sets();
    let torch = sets
        .iter()
        .position(|set| set.name == "torch")
        .expect("the torch is used");
    let image = &compiled.sprites()[usize::from(sets[torch].first)];
    assert_eq!((image.name.as_str(), image.width), ("torch", 16));
    for map in compiled.maps() {
        assert!(
            map.things
                .iter()
                .filter(|t| usize::from(t.sprite) == torch)
                .all(|t| t.radius == 8 && t.z == 0 && t.flags == 0),
            "{}: shipped torches stand on the floor, radius 8",
            map.name
        );
    }
}

/// The shipped sets with several images (placed in a scratch copy of the assets): the flame's
/// four frames and the statue's eight rotations are each different pictures of one size.
#[test]
fn shipped_animated_and_rotated_sets_compile() {
    let scratch = Scratch::new("shipped-sets");
    for folder in ["textures", "sprites", "sky"] {
        let from = shipped_assets().join(folder);
        for entry in std::fs::read_dir(&from).expect("shipped folder") {
            let path = entry.expect("entry").path();
            let name = path
                .file_name()
                .expect("name")
                .to_string_lossy()
                .into_owned();
            scratch.write(
                &format!("{folder}/{name}"),
                &std::fs::read(&path).expect("shipped file"),
            );
        }
    }
    scratch.write(
        "maps/room.map",
        b"vertex a 0 0\nvertex b 128 0\nvertex c 128 128\nvertex d 0 128\n\
          sector room floor=0 ceil=96 floor_tex=stone ceil_tex=stone\n\
          wall a b tex=brick\nwall b c tex=brick\nwall c d tex=brick\nwall d a tex=brick\n\
          player 64 64\nthing flame 32 32 anim=6\nthing statue 96 96 angle=90 solid\n",
    );
    let compiled = compile_dir(&scratch.dir).unwrap_or_else(|e| panic!("{e}"));
    let sets: Vec<_> = compiled.sprite_sets().iter().map(|s| s.set()).collect();
    assert_eq!(
        sets.iter()
            .map(|s| (s.name, s.first, s.frames, s.rotations))
            .collect::<Vec<_>>(),
        [("flame", 0, 4, 1), ("statue", 4, 1, 8)]
    );
    let images = compiled.sprites();
    assert_eq!(images.len(), 12);
    for (range, size) in [(0..4, (16, 24)), (4..12, (24, 48))] {
        for a in range.clone() {
            assert_eq!(
                (images[a].width, images[a].height),
                size,
                "{}",
                images[a].name
            );
            for b in range.clone().filter(|&b| b > a) {
                assert_ne!(
                    images[a].posts, images[b].posts,
                    "{} and {} differ",
                    images[a].name, images[b].name
                );
            }
        }
    }
    assert_eq!(images[4].name, "statue.r0");
    let map = &compiled.maps()[0];
    // The solid statue first in its sector's things, then the flame (anim=6).
    let ticks: Vec<u16> = map.things.iter().map(|t| t.frame_ticks).collect();
    assert_eq!(ticks, [8, 6]);
}

/// A wall as the naive reader sees it: its start point and the sector its portal names.
type WallStart = ((i32, i32), Option<String>);

/// Reads bench.map with a deliberately naive parser (no validation) and returns, per sector
/// name, its loop of wall start coordinates and the neighbour each wall names.
fn naive_sectors(text: &str) -> BTreeMap<String, Vec<WallStart>> {
    let mut vertices = HashMap::new();
    let mut sectors: BTreeMap<String, Vec<WallStart>> = BTreeMap::new();
    let mut current = String::new();
    for line in text.lines().map(|l| l.split('#').next().unwrap_or("")) {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["vertex", name, x, y] => {
                vertices.insert(
                    name.to_string(),
                    (x.parse().expect("x"), y.parse().expect("y")),
                );
            }
            ["sector", name, ..] => {
                current = name.to_string();
                sectors.insert(current.clone(), Vec::new());
            }
            ["wall", start, _end, rest @ ..] => {
                let portal = rest
                    .iter()
                    .find_map(|w| w.strip_prefix("portal="))
                    .map(str::to_string);
                sectors
                    .get_mut(&current)
                    .expect("sector")
                    .push((vertices[*start], portal));
            }
            _ => {}
        }
    }
    sectors
}

#[test]
fn bench_map_round_trips_to_the_same_geometry() {
    let text = std::fs::read_to_string(shipped_assets().join("maps/bench.map")).expect("bench.map");
    let written = naive_sectors(&text);
    let order: Vec<&String> = {
        // Sector ids follow file order.
        let mut names = Vec::new();
        for line in text.lines() {
            if let Some(rest) = line.strip_prefix("sector ") {
                names.push(rest.split_whitespace().next().expect("name"));
            }
        }
        names
            .iter()
            .map(|n| written.keys().find(|k| k == n).expect("known"))
            .collect()
    };
    let compiled = compiled();
    let map = compiled.map("bench").expect("bench");
    assert_eq!(map.sectors.len(), written.len());
    for (index, sector) in map.sectors.iter().enumerate() {
        let name = order[index];
        let derived: Vec<WallStart> = map
            .sector_walls(sector)
            .iter()
            .map(|w| {
                let v = map.vertices[usize::from(w.start)];
                (
                    (v.x, v.y),
                    w.neighbour().map(|n| order[usize::from(n)].clone()),
                )
            })
            .collect();
        assert_eq!(derived, written[name], "sector {name}");
    }
}

#[test]
fn bench_map_meets_its_design() {
    let compiled = compiled();
    let map = compiled.map("bench").expect("bench");
    let portal_sides = map.walls.iter().filter(|w| w.neighbour().is_some()).count();
    assert!(
        map.sectors.len() >= 30,
        "thesis scale: {} sectors",
        map.sectors.len()
    );
    assert!(portal_sides >= 60);
    let diagonal = map.walls.iter().any(|w| {
        let (a, b) = (point(&map, w.start), point(&map, w.end));
        a.0 != b.0 && a.1 != b.1
    });
    assert!(diagonal, "non-orthogonal walls");
    let window = map.walls.iter().any(|w| {
        w.neighbour().is_some() && w.upper_texture != NO_TEXTURE && w.lower_texture != NO_TEXTURE
    });
    assert!(
        window,
        "a window: a portal with both an upper and a lower strip"
    );
    assert!(
        map.sectors.iter().any(|s| s.ceil_texture == SKY),
        "a courtyard under the sky"
    );
    let lights: Vec<u8> = map.sectors.iter().map(|s| s.light).collect();
    assert!(
        lights.iter().any(|&l| l < 64) && lights.iter().any(|&l| l > 192),
        "light and dark"
    );

    // Portal middles (issue 17): a grate bars the passage north from the hall, on both sides;
    // the gallery's windows hold translucent leaded glass; one of the hall's lamps is
    // translucent, so the ROM ships the blend table.
    let sector_named = |name: &str| {
        let text = std::fs::read_to_string(shipped_assets().join("maps/bench.map")).expect("bench");
        text.lines()
            .filter_map(|l| l.strip_prefix("sector "))
            .position(|l| l.split_whitespace().next() == Some(name))
            .expect("a bench sector")
    };
    let portal = |from: &str, to: &str| {
        let (from, to) = (sector_named(from), sector_named(to));
        *map.sector_walls(&map.sectors[from])
            .iter()
            .find(|w| w.neighbour().map(usize::from) == Some(to))
            .expect("a portal")
    };
    let set = |name: &str| {
        compiled
            .sprite_sets()
            .iter()
            .position(|s| s.name == name)
            .expect("a used set") as u16
    };
    for (from, to) in [("hall_n", "passage"), ("passage", "hall_n")] {
        let wall = portal(from, to);
        assert_eq!((wall.middle, wall.flags), (set("grate"), 0));
    }
    for k in 1..=3 {
        let window = format!("window_{k}");
        for wall in [portal("gallery", &window), portal(&window, "gallery")] {
            assert_eq!(
                (wall.middle, wall.flags),
                (set("window"), WALL_MIDDLE_TRANSLUCENT | WALL_MIDDLE_BLOCKS)
            );
        }
    }
    let middles = map.walls.iter().filter(|w| w.middle != NO_TEXTURE).count();
    assert_eq!(middles, 8, "the grate's and the three windows' two sides");
    let translucent = map
        .things
        .iter()
        .filter(|t| t.flags & THING_TRANSLUCENT != 0);
    assert_eq!(translucent.count(), 1, "one translucent lamp");
    assert!(compiled.blend().is_some(), "something is translucent");

    // Walk from the start with the player's rules: step up at most 16, and not through a
    // portal that blocks. Every sector reached must leave 64 units of headroom, and the walk
    // must climb a staircase of 4+ steps.
    let mut reached = vec![false; map.sectors.len()];
    let mut queue = VecDeque::from([usize::from(map.player_start.sector)]);
    reached[usize::from(map.player_start.sector)] = true;
    let mut longest_climb = vec![0usize; map.sectors.len()];
    while let Some(index) = queue.pop_front() {
        let here = map.sectors[index];
        assert!(
            here.ceil_z - here.floor_z >= 64,
            "headroom in walkable sector {index}"
        );
        for wall in map.sector_walls(&here) {
            let Some(next) = wall.neighbour().map(usize::from) else {
                continue;
            };
            if wall.flags & WALL_MIDDLE_BLOCKS != 0 {
                continue;
            }
            let there = map.sectors[next];
            let rise = there.floor_z - here.floor_z;
            if rise > 16 || there.ceil_z - there.floor_z < 64 {
                continue;
            }
            if rise > 0 {
                longest_climb[next] = longest_climb[next].max(longest_climb[index] + 1);
            }
            if !reached[next] {
                reached[next] = true;
                queue.push_back(next);
            }
        }
    }
    // The windows (closed by their glass), the crawlway's den and the ledge are off the walk's
    // rules; the rest is walkable.
    let walkable = reached.iter().filter(|&&r| r).count();
    assert!(walkable >= 30, "most of the map is walkable: {walkable}");
    assert!(
        longest_climb.iter().any(|&c| c >= 4),
        "a staircase of 16-unit steps"
    );
}

#[test]
fn written_blobs_read_back() {
    let compiled = compiled();
    let out = Scratch::new("shipped-out");
    compiled.write_to(&out.dir).expect("write");
    let texels = std::fs::read(out.path("assets_texels.bin")).expect("texel blob");
    let source = std::fs::read_to_string(out.path("assets.rs")).expect("assets.rs");
    let mut offset = 0;
    for texture in compiled.textures() {
        for chain in [&texture.columns, &texture.rows] {
            assert_eq!(
                &texels[offset..offset + chain.len()],
                &chain[..],
                "{}",
                texture.name
            );
            let slice = format!("sub_slice(&TEXEL_BLOB.0, {offset}, {})", chain.len());
            assert!(
                source.contains(&slice),
                "{} is sliced as {slice}",
                texture.name
            );
            offset = (offset + chain.len()).next_multiple_of(4);
        }
    }
    assert_eq!(offset, texels.len());
    let sprites = std::fs::read(out.path("assets_sprites.bin")).expect("sprite blob");
    assert_eq!(
        &sprites[..compiled.sprites()[0].posts.len()],
        &compiled.sprites()[0].posts[..]
    );
    let report = compiled.size_report();
    for kind in [
        "palette",
        "colormap",
        "textures",
        "sky",
        "sprites",
        "map tables",
        "IWRAM",
        "EWRAM",
    ] {
        assert!(report.contains(kind), "size report names {kind}:\n{report}");
    }
}

#[test]
fn generator_reproduces_the_committed_assets() {
    let out = Scratch::new("generated");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_gen-assets"))
        .arg(&out.dir)
        .stdout(std::process::Stdio::null())
        .status()
        .expect("run gen-assets");
    assert!(status.success());
    let shipped = shipped_assets();
    let mut compared = 0;
    for folder in ["textures", "sky", "sprites", "maps"] {
        for entry in std::fs::read_dir(out.path(folder)).expect("generated folder") {
            let path = entry.expect("entry").path();
            let name = path.file_name().expect("file name");
            let committed = std::fs::read(shipped.join(folder).join(name))
                .unwrap_or_else(|_| panic!("{folder}/{name:?} is generated but not committed"));
            assert!(
                committed == std::fs::read(&path).expect("generated file"),
                "{folder}/{name:?} differs from the generator's output; rerun gen-assets"
            );
            compared += 1;
        }
    }
    assert!(compared >= 15);
}

#[test]
fn examples_in_the_format_doc_compile() {
    let doc_path = shipped_assets().join("../docs/MAP_FORMAT.md");
    let doc = std::fs::read_to_string(doc_path).expect("docs/MAP_FORMAT.md");
    let catalog = portalcast_assets::Catalog::new(
        [
            "brick", "ceiling", "grass", "marble", "metal", "step", "stone", "tiles", "trim",
            "wood",
        ],
        ["torch"],
        true,
    )
    .with_sprite_size("torch", 16, 48);
    let (mut examples, mut movers, mut triggers, mut slopes, mut links) = (0, 0, 0, 0, 0);
    let mut lights = Vec::new();
    for section in doc.split("### Example").skip(1) {
        let block = section
            .split("```")
            .nth(1)
            .expect("an example is a fenced block");
        let file = if block.contains("\ngrid\n") {
            "example.grid"
        } else {
            "example.map"
        };
        match portalcast_assets::compile_map_str(file, block, &catalog) {
            Ok(map) => {
                movers += map.movers.len();
                triggers += map.triggers.len();
                slopes += map.slopes.len();
                links += map
                    .layer_links
                    .iter()
                    .filter(|link| link.above != portalcast_format::NO_LINK)
                    .count();
                lights.extend(map.lights.iter().map(|l| (l.kind, l.low, l.period, l.tag)));
            }
            Err(errors) => {
                panic!("the {file} example in docs/MAP_FORMAT.md does not compile:\n{errors}")
            }
        }
        examples += 1;
    }
    assert_eq!(examples, 5);
    // The slopes' example: the ramp, the attic and the bank.
    assert_eq!(slopes, 3);
    // The room over room example: the two pits' open ceilings.
    assert_eq!(links, 2);
    // The movers' example: a door and a lift, a switch and a walk-over line; the grid's door.
    assert_eq!((movers, triggers), (3, 2));
    // The movers' example's light effects: the hall's glow, the corridor's flicker (its default
    // period) and the ledge's switched light, turned by the lift's tag.
    assert_eq!(
        lights,
        [
            (portalcast_format::LIGHT_GLOW, 100, 240, 0),
            (portalcast_format::LIGHT_FLICKER, 40, 4, 0),
            (portalcast_format::LIGHT_SWITCHED, 40, 0, 1),
        ]
    );
}
