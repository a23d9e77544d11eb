//! The oracle on hand-built maps, with every expected value worked out in the comments.
//!
//! Common set-up unless a test says otherwise: a 240×160 view, `focal_x = focal_y = 120`,
//! horizon at 80, eye at `(0, 0)`, height 32, looking along +x (angle 0). Column `c` has slope
//! `m = (c + ½ − 120)/120` and ray `D = (1, m)`; row `y` has `k = (y + ½ − 80)/120` and height
//! `h(t) = 32 − k·t`. Room A is `x ∈ [−64, 64]`, `y ∈ [−32, 32]`, floor 0, ceiling 64; its walls
//! are 0 north `(−64,−32)→(64,−32)`, 1 east `(64,−32)→(64,32)`, 2 south, 3 west. The centre
//! column 120 has `m = 1/240`, so it meets `x = 64` at `t = 64` and `x = 192` at `t = 192`.

use std::collections::BTreeSet;

use portalcast::render::light::light_row;
use portalcast::render::surface::THING_DEPTH_MIN;
use portalcast_format::{
    BlendTable, Colormap, MapTables, PlayerSize, PlayerStart, Sector, Sky, Sprite, SpriteSet,
    Texture, Thing, Vertex, Wall, NO_PORTAL, NO_TEXTURE, SKY, THING_HANGING, THING_TRANSLUCENT,
    TRANSPARENT, WALL_MIDDLE_TRANSLUCENT,
};
use portalcast_oracle::{
    angle_from_bits, angle_to_bits, compare, compare_with_row_tolerance, find_sector, render,
    sample_poses, surface_colour, write_diff_png, Assets, Camera, Frame, Lighting, Surface, View,
};

// ---------------------------------------------------------------------------------------------
// Fixtures

/// Texture slots of the fixtures.
const WALL_TEX: u16 = 0;
const FLOOR_TEX: u16 = 1;
const CEIL_TEX: u16 = 2;
const STRIP_TEX: u16 = 3;

/// Texel `(u, v)` of mip level `level` of texture `slot`: distinct for every `(u, v)` of level 0
/// of one slot, so a wrong coordinate shows.
fn pattern(slot: u16, level: u8, u: usize, v: usize) -> u8 {
    ((slot as usize * 64 + level as usize * 37 + u * 8 + v) % 256) as u8
}

/// An 8×8 texture with 4 mip levels in both layouts.
struct OwnedTexture {
    columns: Vec<u8>,
    rows: Vec<u8>,
}

impl OwnedTexture {
    fn new(slot: u16) -> OwnedTexture {
        let (mut columns, mut rows) = (Vec::new(), Vec::new());
        for level in 0..4u8 {
            let side = 8usize >> level;
            for u in 0..side {
                for v in 0..side {
                    columns.push(pattern(slot, level, u, v));
                }
            }
            for v in 0..side {
                for u in 0..side {
                    rows.push(pattern(slot, level, u, v));
                }
            }
        }
        OwnedTexture { columns, rows }
    }

    fn texture(&self) -> Texture<'_> {
        Texture {
            name: "t",
            width_log2: 3,
            height_log2: 3,
            mip_count: 4,
            columns: &self.columns,
            rows: &self.rows,
        }
    }
}

/// The sky texel of column `u` (of 8), row `v` (of `height`).
fn sky_pattern(u: usize, v: usize) -> u8 {
    ((v + 31 * u) % 256) as u8
}

/// Lighting row `r` maps index `i` to `(3i + r) mod 256`: every row differs from the identity.
fn colormap() -> Box<Colormap> {
    let mut map = Box::new([[0u8; 256]; 32]);
    for (r, row) in map.iter_mut().enumerate() {
        for (i, entry) in row.iter_mut().enumerate() {
            *entry = ((3 * i + r) % 256) as u8;
        }
    }
    map
}

/// A sprite image in the format's posts layout (`portalcast_format::Sprite`).
struct OwnedSprite {
    width: u16,
    height: u16,
    posts: Vec<u8>,
}

impl OwnedSprite {
    /// The `width × height` image whose texel `(u, v)` (`v` 0 at the top) is `texel(u, v)`,
    /// `None` where it is transparent: each column's opaque runs become posts.
    fn new(width: u16, height: u16, texel: impl Fn(usize, usize) -> Option<u8>) -> OwnedSprite {
        let (w, h) = (usize::from(width), usize::from(height));
        let mut posts = vec![0u8; 4 * w];
        for u in 0..w {
            let offset = posts.len() as u32;
            posts[4 * u..4 * u + 4].copy_from_slice(&offset.to_le_bytes());
            let count_at = posts.len();
            posts.push(0);
            let mut v = 0;
            while v < h {
                if texel(u, v).is_none() {
                    v += 1;
                    continue;
                }
                let top = v;
                let mut run = Vec::new();
                while v < h && run.len() < 255 {
                    let Some(index) = texel(u, v) else { break };
                    assert_ne!(index, TRANSPARENT, "an opaque texel is never 0");
                    run.push(index);
                    v += 1;
                }
                posts.extend([top as u8, run.len() as u8]);
                posts.extend(&run);
                posts.push(*run.last().unwrap());
                posts[count_at] += 1;
            }
        }
        OwnedSprite {
            width,
            height,
            posts,
        }
    }

    fn sprite(&self) -> Sprite<'_> {
        Sprite {
            name: "s",
            width: self.width,
            height: self.height,
            posts: &self.posts,
        }
    }
}

/// Sprite slots of the fixtures: an 8×16 image with holes (column 0 empty, and every texel with
/// `(u + v) mod 4 = 3`), an 8×16 opaque one, and an 8×24 grate for portal middles (columns 3
/// and 7 and rows 7, 15 and 23 transparent).
const HOLED_SPRITE: u16 = 0;
const SOLID_SPRITE: u16 = 1;
const GRATE_SPRITE: u16 = 2;

/// Texel `(u, v)` of the grate: distinct for every opaque `(u, v)`.
fn grate(u: usize, v: usize) -> Option<u8> {
    (u % 4 != 3 && v % 8 != 7).then_some((40 + 24 * u + v) as u8)
}

/// The fixtures' blend table: `blend[b][f] = (7b + 3f) mod 255 + 1`, never 0, and different
/// with the arguments swapped, so a blend the wrong way round shows.
fn blended(behind: u8, front: u8) -> u8 {
    ((7 * usize::from(behind) + 3 * usize::from(front)) % 255 + 1) as u8
}

fn blend_table() -> Box<BlendTable> {
    let mut table: Box<BlendTable> = vec![[0u8; 256]; 256].into_boxed_slice().try_into().unwrap();
    for (behind, row) in table.iter_mut().enumerate() {
        for (front, entry) in row.iter_mut().enumerate() {
            *entry = blended(behind as u8, front as u8);
        }
    }
    table
}

/// Texel `(u, v)` of the holed sprite.
fn holed(u: usize, v: usize) -> Option<u8> {
    (u != 0 && (u + v) % 4 != 3).then_some((1 + 16 * u + v) as u8)
}

/// Texel `(u, v)` of the solid sprite.
fn solid(u: usize, v: usize) -> u8 {
    (128 + 16 * u + v) as u8
}

struct Fixture {
    textures: Vec<OwnedTexture>,
    sky_texels: Vec<u8>,
    sky_height: u16,
    colormap: Box<Colormap>,
    sprites: Vec<OwnedSprite>,
    blend: Option<Box<BlendTable>>,
}

impl Fixture {
    fn new(sky_height: u16) -> Fixture {
        let mut sky_texels = Vec::new();
        for u in 0..8 {
            for v in 0..usize::from(sky_height) {
                sky_texels.push(sky_pattern(u, v));
            }
        }
        Fixture {
            textures: (0..4).map(OwnedTexture::new).collect(),
            sky_texels,
            sky_height,
            colormap: colormap(),
            sprites: vec![
                OwnedSprite::new(8, 16, holed),
                OwnedSprite::new(8, 16, |u, v| Some(solid(u, v))),
                OwnedSprite::new(8, 24, grate),
            ],
            blend: None,
        }
    }

    fn render(&self, map: &MapTables, camera: &Camera, view: &View) -> Frame {
        // One still image a set.
        let sets: Vec<SpriteSet> = (0..self.sprites.len())
            .map(|first| SpriteSet {
                name: "s",
                first: first as u16,
                frames: 1,
                rotations: 1,
            })
            .collect();
        self.render_with_sets(map, camera, view, &sets)
    }

    fn render_with_sets(
        &self,
        map: &MapTables,
        camera: &Camera,
        view: &View,
        sprite_sets: &[SpriteSet],
    ) -> Frame {
        let textures: Vec<Texture> = self.textures.iter().map(OwnedTexture::texture).collect();
        let sky = Sky {
            width_log2: 3,
            height: self.sky_height,
            texels: &self.sky_texels,
        };
        let sprites: Vec<Sprite> = self.sprites.iter().map(OwnedSprite::sprite).collect();
        let assets = Assets {
            textures: &textures,
            sky: &sky,
            colormap: &self.colormap,
            sprites: &sprites,
            sprite_sets,
            blend: self.blend.as_deref(),
        };
        render(map, &assets, camera, view)
    }
}

struct OwnedMap {
    vertices: Vec<Vertex>,
    walls: Vec<Wall>,
    sectors: Vec<Sector>,
    things: Vec<Thing>,
    sector_things: Vec<u16>,
}

impl OwnedMap {
    /// Places `things`, which must be in sector order (the map's table is grouped by sector).
    fn with_things(mut self, things: Vec<Thing>) -> OwnedMap {
        assert!(things
            .windows(2)
            .all(|pair| pair[0].sector <= pair[1].sector));
        self.sector_things = (0..=self.sectors.len())
            .map(|sector| {
                things
                    .iter()
                    .filter(|t| usize::from(t.sector) < sector)
                    .count() as u16
            })
            .collect();
        self.things = things;
        self
    }

    fn tables(&self) -> MapTables<'_> {
        MapTables {
            name: "test",
            vertices: &self.vertices,
            walls: &self.walls,
            sectors: &self.sectors,
            player_start: PlayerStart {
                x_fx8: 0,
                y_fx8: 0,
                angle: 0,
                sector: 0,
                size: PlayerSize::NATIVE,
            },
            things: &self.things,
            sector_things: &self.sector_things,
            movers: &[],
            triggers: &[],
            lights: &[],
            wall_twins: &[],
            slopes: &[],
            layer_links: &[],
        }
    }
}

fn wall(start: u16, end: u16, portal: u16) -> Wall {
    let solid = portal == NO_PORTAL;
    Wall {
        start,
        end,
        portal,
        texture: if solid { WALL_TEX } else { NO_TEXTURE },
        upper_texture: if solid { NO_TEXTURE } else { STRIP_TEX },
        lower_texture: if solid { NO_TEXTURE } else { STRIP_TEX },
        x_offset: 0,
        y_offset: 0,
        // Only the engine reads it; these maps are drawn by the oracle, which measures each
        // wall itself.
        length_fx8: 0,
        middle: NO_TEXTURE,
        flags: 0,
    }
}

fn sector(first_wall: u16, floor_z: i32, ceil_z: i32, ceil_texture: u16, light: u8) -> Sector {
    Sector {
        first_wall,
        wall_count: 4,
        floor_z,
        ceil_z,
        floor_texture: FLOOR_TEX,
        ceil_texture,
        light,
        links: 0,
        slope: portalcast_format::NO_SLOPE,
    }
}

/// Room A alone, `x ∈ [−64, east]`; the east wall (1) is solid, or a portal to `east_portal`.
fn room(east: i32, east_portal: u16) -> OwnedMap {
    OwnedMap {
        vertices: vec![
            Vertex { x: -64, y: -32 },
            Vertex { x: east, y: -32 },
            Vertex { x: east, y: 32 },
            Vertex { x: -64, y: 32 },
        ],
        walls: vec![
            wall(0, 1, NO_PORTAL),
            wall(1, 2, east_portal),
            wall(2, 3, NO_PORTAL),
            wall(3, 0, NO_PORTAL),
        ],
        sectors: vec![sector(0, 0, 64, CEIL_TEX, 128)],
        things: Vec::new(),
        sector_things: Vec::new(),
    }
}

/// Room A with its east wall a portal to room B, `x ∈ [64, 192]`, `y ∈ [−32, 32]`. B's walls are
/// 4 north `(64,−32)→(192,−32)`, 5 east `(192,−32)→(192,32)`, 6 south, 7 the portal back.
fn two_rooms(
    b_floor: i32,
    b_ceil: i32,
    a_ceil_texture: u16,
    b_ceil_texture: u16,
    b_light: u8,
) -> OwnedMap {
    let mut map = room(64, 1);
    map.sectors[0].ceil_texture = a_ceil_texture;
    map.vertices
        .extend([Vertex { x: 192, y: -32 }, Vertex { x: 192, y: 32 }]);
    map.walls.extend([
        wall(1, 4, NO_PORTAL),
        wall(4, 5, NO_PORTAL),
        wall(5, 2, NO_PORTAL),
        wall(2, 1, 0),
    ]);
    let mut b = sector(4, b_floor, b_ceil, b_ceil_texture, b_light);
    b.floor_texture = CEIL_TEX;
    map.sectors.push(b);
    map
}

fn view(lighting: Lighting) -> View {
    View {
        width: 240,
        height: 160,
        focal_x: 120.0,
        focal_y: 120.0,
        horizon_y: 80.0,
        lighting,
        tick: 0,
    }
}

fn centre_camera() -> Camera {
    Camera {
        x: 0.0,
        y: 0.0,
        eye_z: 32.0,
        angle: 0.0,
        sector: Some(0),
    }
}

/// The surfaces of column `x`, as `(first row, last row, surface)` runs.
fn runs(frame: &Frame, x: usize) -> Vec<(usize, usize, Surface)> {
    let mut runs: Vec<(usize, usize, Surface)> = Vec::new();
    for y in 0..frame.height {
        let surface = frame.surface(x, y);
        match runs.last_mut() {
            Some(run) if run.2 == surface => run.1 = y,
            _ => runs.push((y, y, surface)),
        }
    }
    runs
}

// ---------------------------------------------------------------------------------------------
// Rendering

/// Room A alone (all solid). Centre column: the ceiling where `h(64) > 64`, i.e. `k < −½`,
/// `y + ½ < 20`: rows 0..=19; the floor where `h(64) < 0`, `k > ½`, `y + ½ > 140`: rows
/// 140..=159; wall 1 between. Row 80 by column: the ray meets `y = −32` before `x = 64` when
/// `m < −½`, `c + ½ < 60` (columns 0..=59, wall 0); symmetrically columns 180..=239 see wall 2.
#[test]
fn single_room_centre_column_and_symmetry() {
    let map = room(64, NO_PORTAL);
    let fixture = Fixture::new(200);
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Off));

    assert_eq!(
        runs(&frame, 120),
        vec![
            (0, 19, Surface::Ceiling(0)),
            (20, 139, Surface::Wall(1)),
            (140, 159, Surface::Floor(0))
        ]
    );
    let row_80: Vec<Surface> = (0..240).map(|x| frame.surface(x, 80)).collect();
    assert!(row_80[..60].iter().all(|&s| s == Surface::Wall(0)));
    assert!(row_80[60..180].iter().all(|&s| s == Surface::Wall(1)));
    assert!(row_80[180..].iter().all(|&s| s == Surface::Wall(2)));
    assert_eq!(frame.depth(120, 80), 64.0);

    // Mirror symmetry: column c ↔ 239 − c swaps walls 0 and 2; row y ↔ 159 − y swaps the
    // ceiling and the floor (the eye is at mid-height, the horizon mid-screen), except on the
    // diagonals |y + ½ − 80| = |c + ½ − 120| of the side-wall columns, where the side wall at
    // `t = 32/|m|` meets the ceiling or floor exactly (`|k|·t = 32`): ties go down the screen,
    // to the wall at the top edge and to the floor at the bottom edge. Column 40 (`m = −0.6625`)
    // rows 0 and 159 are such an exact tie in f64.
    assert_eq!(
        (frame.surface(40, 0), frame.surface(40, 159)),
        (Surface::Wall(0), Surface::Floor(0))
    );
    let mirror_x = |s: Surface| match s {
        Surface::Wall(0) => Surface::Wall(2),
        Surface::Wall(2) => Surface::Wall(0),
        other => other,
    };
    let mirror_y = |s: Surface| match s {
        Surface::Ceiling(0) => Surface::Floor(0),
        Surface::Floor(0) => Surface::Ceiling(0),
        other => other,
    };
    let mut ties = 0;
    for y in 0..160 {
        for x in 0..240 {
            let surface = frame.surface(x, y);
            assert_eq!(
                frame.surface(239 - x, y),
                mirror_x(surface),
                "column mirror at ({x}, {y})"
            );
            let mirrored = frame.surface(x, 159 - y);
            // Each pair once, from its top pixel.
            if y < 80 && mirrored != mirror_y(surface) {
                let on_diagonal = (y as f64 + 0.5 - 80.0).abs() == (x as f64 + 0.5 - 120.0).abs();
                let tie = matches!(surface, Surface::Wall(_)) && mirrored == Surface::Floor(0);
                assert!(
                    on_diagonal && tie,
                    "row mirror at ({x}, {y}): {surface:?} / {mirrored:?}"
                );
                ties += 1;
            }
        }
    }
    assert!(ties >= 1);
}

/// Texels of room A, lighting off. Wall 1 with offsets (3, 5) at (120, 80): hit at y = 64/240,
/// `u = 32 + 0.2667 + 3 = 35.27` → 35 mod 8 = 3; `h = 32 − 64·(0.5/120) = 31.73`,
/// `v = 64 − 31.73 + 5 = 37.27` → 5; depth 64 < 2·120: level 0.
/// Floor at (120, 150): `k = 70.5/120`, `t = 32/k = 54.47`, point (54.47, 0.227) → (6, 0).
/// Ceiling at (120, 5): `k = −74.5/120`, `t = −32/k = 51.54`, point (51.54, 0.215) → (3, 0).
#[test]
fn single_room_texels() {
    let mut map = room(64, NO_PORTAL);
    map.walls[1].x_offset = 3;
    map.walls[1].y_offset = 5;
    let fixture = Fixture::new(200);
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Off));

    assert_eq!(frame.index(120, 80), pattern(WALL_TEX, 0, 3, 5));
    assert_eq!(frame.surface(120, 150), Surface::Floor(0));
    assert_eq!(frame.index(120, 150), pattern(FLOOR_TEX, 0, 6, 0));
    // Rows are cast through the centre moved down by TIE_NUDGE.
    let row_offset = 70.5 + portalcast_oracle::TIE_NUDGE;
    assert!((frame.depth(120, 150) - 32.0 / (row_offset / 120.0)).abs() < 1e-9);
    assert_eq!(frame.surface(120, 5), Surface::Ceiling(0));
    assert_eq!(frame.index(120, 5), pattern(CEIL_TEX, 0, 3, 0));
}

/// A corridor A, `x ∈ [−64, 1000]`, lit by depth (light 128). The east wall at `t = 1000`:
/// `1000/120 = 8.3` → level 3 (1×1, texel (0, 0)); light `128 + 32 − 1000/16 = 98` → row 12.
/// Floor at (120, 92): `k = 12.5/120`, `t = 307.2`, `307.2/120 = 2.56` → level 1 (4×4); point
/// (307.2, 1.28): `(307 mod 8) >> 1 = 1`, `(1 mod 8) >> 1 = 0`; light `160 − 307/16 = 141` →
/// row 17.
#[test]
fn corridor_mip_levels_and_depth_light() {
    let map = room(1000, NO_PORTAL);
    let fixture = Fixture::new(200);
    let frame = fixture.render(
        &map.tables(),
        &centre_camera(),
        &view(Lighting::SectorDepth),
    );

    assert_eq!(frame.surface(120, 80), Surface::Wall(1));
    assert_eq!(
        frame.index(120, 80),
        fixture.colormap[12][usize::from(pattern(WALL_TEX, 3, 0, 0))]
    );
    assert_eq!(frame.surface(120, 92), Surface::Floor(0));
    assert_eq!(
        frame.index(120, 92),
        fixture.colormap[17][usize::from(pattern(FLOOR_TEX, 1, 1, 0))]
    );
}

/// A's east wall is a portal to B (floor 20, ceiling 44, light 200). Centre column:
/// - A's ceiling where `h(64) > 64`, `k < −½`, `y + ½ < 20`: rows 0..=19;
/// - upper strip where `h(64) > 44`, `k < −3/16`, `y + ½ < 57.5`: rows 20..=56;
/// - B's ceiling where `h(192) > 44`, `k < −1/16`, `y + ½ < 72.5`: rows 57..=71;
/// - B's east wall 5 while `h(192) > 20`, `k < 1/16`, `y + ½ < 87.5`: rows 72..=86;
/// - B's floor while `h(64) > 20`, `k < 3/16`, `y + ½ < 102.5`: rows 87..=101;
/// - lower strip while `h(64) > 0`, `k < ½`: rows 102..=139; A's floor below.
///
/// Rows 57, 72, 87 and 102 sit exactly on an edge (`k` and `t` are exact in f64, so `h` is
/// exactly 44, 44, 20 and 20): each goes to the surface below the edge on screen, as the
/// engine's row rule `y0 ≤ y + ½ < y1` gives them.
#[test]
fn portal_to_a_raised_room_shows_strips_and_the_far_floor() {
    let mut map = two_rooms(20, 44, CEIL_TEX, CEIL_TEX, 200);
    map.walls[5].x_offset = 2;
    let fixture = Fixture::new(200);
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Sector));

    assert_eq!(
        runs(&frame, 120),
        vec![
            (0, 19, Surface::Ceiling(0)),
            (20, 56, Surface::Upper(1)),
            (57, 71, Surface::Ceiling(1)),
            (72, 86, Surface::Wall(5)),
            (87, 101, Surface::Floor(1)),
            (102, 139, Surface::Lower(1)),
            (140, 159, Surface::Floor(0)),
        ]
    );
    // Strips take A's light (128 → row 16), B's surfaces B's (200 → row 25). Wall 1 has
    // `u = 32.27` → 0.
    let cm = &fixture.colormap;
    // Upper at row 30: `k = −49.5/120`, `h(64) = 58.4`, anchored at A's ceiling: `v = 5.6` → 5.
    assert_eq!(
        frame.index(120, 30),
        cm[16][usize::from(pattern(STRIP_TEX, 0, 0, 5))]
    );
    // Lower at row 130: `k = 50.5/120`, `h(64) = 5.07`, anchored at B's floor: `v = 14.93` → 6
    // (A's floor would give `floor(−5.07) mod 8 = 2`).
    assert_eq!(
        frame.index(120, 130),
        cm[16][usize::from(pattern(STRIP_TEX, 0, 0, 6))]
    );
    // B's floor at row 100: `k = 20.5/120`, `t = 12/k = 70.24`, point (70.24, 0.29) → (6, 0).
    assert_eq!(
        frame.index(120, 100),
        cm[25][usize::from(pattern(CEIL_TEX, 0, 6, 0))]
    );
    // Wall 5 at row 75: hit y = 0.8, `u = 32.8 + 2` → 2; `h = 32 + 192·4.5/120 = 39.2`,
    // `v = 44 − 39.2 = 4.8` → 4.
    assert_eq!(
        frame.index(120, 75),
        cm[25][usize::from(pattern(WALL_TEX, 0, 2, 4))]
    );
    assert_eq!(frame.depth(120, 75), 192.0);
}

/// Both rooms open to the sky (B's ceiling 48, floor 0): rows 0..=69 of the centre column
/// are all sky (A's where `h(64) > 64`: rows 0..=19; the upper strip where `h(64) > 48`,
/// `y + ½ < 50`, never drawn as both ceilings are sky; B's where `h(192) > 48`, `y + ½ < 70`);
/// B's wall 5 while `h(192) > 0`, `k < 1/6`, `y + ½ < 100`: rows 70..=99; B's floor while
/// `h(64) > 0`: rows 100..=139.
/// Sky texels: column 120 looks at `atan(1/240) > 0` → sky column 0, column 119 at `−atan(1/240)`
/// → column 7; row y → `floor(y + ½ − 80) + 200/2 = y + 20`; never lit (light 200, lit view).
#[test]
fn sky_sectors_show_the_unlit_panorama() {
    let map = two_rooms(0, 48, SKY, SKY, 200);
    let fixture = Fixture::new(200);
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Sector));

    assert_eq!(
        runs(&frame, 120),
        vec![
            (0, 69, Surface::Sky),
            (70, 99, Surface::Wall(5)),
            (100, 139, Surface::Floor(1)),
            (140, 159, Surface::Floor(0)),
        ]
    );
    for y in [0, 19, 35, 69] {
        assert_eq!(frame.index(120, y), sky_pattern(0, y + 20), "row {y}");
        assert_eq!(frame.index(119, y), sky_pattern(7, y + 20), "row {y}");
        assert_eq!(frame.depth(120, y), f64::INFINITY);
    }

    // Only B open to the sky: the strip is drawn, B's ceiling is sky.
    let map = two_rooms(0, 48, CEIL_TEX, SKY, 200);
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Sector));
    assert_eq!(
        runs(&frame, 120)[..3],
        [
            (0, 19, Surface::Ceiling(0)),
            (20, 49, Surface::Upper(1)),
            (50, 69, Surface::Sky)
        ]
    );

    // A 100-row panorama: row y → `clamp(y − 80 + 50)`, so rows 0..=30 show its top row.
    let fixture = Fixture::new(100);
    let map = two_rooms(0, 48, SKY, SKY, 200);
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Sector));
    assert_eq!(frame.index(120, 0), sky_pattern(0, 0));
    assert_eq!(frame.index(120, 30), sky_pattern(0, 0));
    assert_eq!(frame.index(120, 31), sky_pattern(0, 1));
    assert_eq!(frame.index(120, 69), sky_pattern(0, 39));

    // Half the rows (80, focal_y 60, horizon 40): the row offset is scaled by 160/80, row y →
    // `floor(2y + 1 − 80) + 100 = 2y + 21`. A's ceiling needs `k = (y + ½ − 40)/60 < −½`:
    // rows 0..=9.
    let fixture = Fixture::new(200);
    let half = View {
        height: 80,
        focal_y: 60.0,
        horizon_y: 40.0,
        ..view(Lighting::Off)
    };
    let frame = fixture.render(&map.tables(), &centre_camera(), &half);
    assert_eq!(frame.surface(120, 9), Surface::Sky);
    assert_eq!(frame.index(120, 0), sky_pattern(0, 21));
    assert_eq!(frame.index(120, 9), sky_pattern(0, 39));
}

/// A square room `[−64, 64]²` with `focal_x = 119.5`: column 239 has `m = 119.5/119.5 = 1`
/// exactly, so its ray passes through the corner (64, 64), the end of wall 1 and the start of
/// wall 2: `s ∈ [0, 1)` gives wall 2. Column 0 (`m = −1`) passes through (64, −64), the end of
/// wall 0 and the start of wall 1: wall 1.
#[test]
fn a_ray_through_a_vertex_takes_the_wall_starting_there() {
    let map = OwnedMap {
        vertices: vec![
            Vertex { x: -64, y: -64 },
            Vertex { x: 64, y: -64 },
            Vertex { x: 64, y: 64 },
            Vertex { x: -64, y: 64 },
        ],
        walls: vec![
            wall(0, 1, NO_PORTAL),
            wall(1, 2, NO_PORTAL),
            wall(2, 3, NO_PORTAL),
            wall(3, 0, NO_PORTAL),
        ],
        sectors: vec![sector(0, 0, 64, CEIL_TEX, 128)],
        things: Vec::new(),
        sector_things: Vec::new(),
    };
    let fixture = Fixture::new(200);
    let view = View {
        focal_x: 119.5,
        ..view(Lighting::Off)
    };
    let frame = fixture.render(&map.tables(), &centre_camera(), &view);
    assert_eq!(frame.surface(239, 80), Surface::Wall(2));
    assert_eq!(frame.surface(0, 80), Surface::Wall(1));
    // 64 up to the TIE_NUDGE the ray is moved by.
    assert!((frame.depth(239, 80) - 64.0).abs() < 1e-5);
}

/// A portal back into its own sector (a broken map) never reaches a surface at the heights the
/// ray keeps between floor and ceiling: after `1 + 8` sectors those pixels are holes. Rows
/// 0..=19 and 140..=159 still hit the ceiling and floor of the first pass.
#[test]
fn portal_loops_end_as_holes() {
    let map = room(64, 0);
    let fixture = Fixture::new(200);
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Off));
    assert_eq!(
        runs(&frame, 120),
        vec![
            (0, 19, Surface::Ceiling(0)),
            (20, 139, Surface::None),
            (140, 159, Surface::Floor(0))
        ]
    );
}

/// A missing texture slot draws texel 0 (then lit: `(3·0 + 16) mod 256 = 16`).
#[test]
fn missing_texture_draws_texel_zero() {
    let mut map = room(64, NO_PORTAL);
    map.walls[1].texture = NO_TEXTURE;
    let fixture = Fixture::new(200);
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Off));
    assert_eq!(
        (frame.surface(120, 80), frame.index(120, 80)),
        (Surface::Wall(1), 0)
    );
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Sector));
    assert_eq!(frame.index(120, 80), 16);
}

// ---------------------------------------------------------------------------------------------
// Things
//
// Things below are 8×16 sprites. Standing on the floor with `z = 8` at depth `z' = 48` on the
// centre line (`x' = 0`), the rectangle is `[−4, 4)` across and heights `[8, 24]`: column `c`
// meets it at `u = floor((c + ½ − 120)·48/120 + 4) = floor((2c − 219)/5)` (columns 110..=129),
// row `y` at `v = floor(24 − (32 − (y + ½ − 80)·48/120)) = floor((2y − 199)/5)` (rows
// 100..=139, over wall 1, whose foot is at row 140 in every column that sees it).

/// A thing at `(x, y)` (whole 1/256 units), radius 4.
fn thing(x: f64, y: f64, sector: u16, sprite: u16, z: i16, flags: u16) -> Thing {
    Thing {
        x_fx8: (x * 256.0) as i32,
        y_fx8: (y * 256.0) as i32,
        angle: 0,
        sprite,
        sector,
        z,
        radius: 4,
        flags,
        frame_ticks: 1,
    }
}

/// The test's own encoder agrees with the format's reader.
#[test]
fn sprite_posts_round_trip() {
    let fixture = Fixture::new(200);
    let sprite = fixture.sprites[usize::from(HOLED_SPRITE)].sprite();
    for u in 0..8 {
        for v in 0..16 {
            assert_eq!(
                sprite.texel(u, v),
                holed(u, v).unwrap_or(TRANSPARENT),
                "({u}, {v})"
            );
        }
    }
    assert_eq!(sprite.column_posts(0).count(), 0);
}

/// A holed sprite standing at depth 48 (see the section's head), lit by depth: each pixel whose
/// `(u, v)` is in the image shows `Thing(0)` at an opaque texel, lit by room A's light at depth
/// 48, and the wall behind (unchanged) at a transparent one; every other pixel is as without the
/// thing. (120, 120): `u = floor(21/5) = 4`, `v = floor(41/5) = 8`, opaque; (120, 118): `v = 7`,
/// `(4 + 7) mod 4 = 3`, a hole.
#[test]
fn a_thing_shows_its_opaque_texels_and_the_wall_through_its_holes() {
    let bare = room(64, NO_PORTAL);
    let map = room(64, NO_PORTAL).with_things(vec![thing(48.0, 0.0, 0, HOLED_SPRITE, 8, 0)]);
    let fixture = Fixture::new(200);
    let lighting = Lighting::SectorDepth;
    let behind = fixture.render(&bare.tables(), &centre_camera(), &view(lighting));
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(lighting));
    let row = light_row(128, 48, lighting).unwrap();

    let (mut shown, mut holes) = (0, 0);
    for y in 0..160i32 {
        for x in 0..240i32 {
            let (u, v) = ((2 * x - 219).div_euclid(5), (2 * y - 199).div_euclid(5));
            let (xs, ys) = (x as usize, y as usize);
            let texel = ((0..8).contains(&u) && (0..16).contains(&v))
                .then(|| holed(u as usize, v as usize))
                .flatten();
            let got = frame.pixel(xs, ys);
            if let Some(texel) = texel {
                shown += 1;
                let index = fixture.colormap[row][usize::from(texel)];
                assert_eq!(got, (Surface::Thing(0), index, 48.0), "({x}, {y})");
            } else {
                holes += usize::from((0..8).contains(&u) && (0..16).contains(&v));
                let expected = (behind.surface(xs, ys), behind.index(xs, ys));
                assert_eq!((got.0, got.1), expected, "({x}, {y})");
                assert_eq!(got.2, behind.depth(xs, ys), "({x}, {y})");
            }
        }
    }
    assert!(shown > 300 && holes > 100, "{shown} shown, {holes} holes");
    assert_eq!(frame.surface(120, 120), Surface::Thing(0));
    assert_eq!(
        frame.index(120, 120),
        fixture.colormap[row][usize::from(holed(4, 8).unwrap())]
    );
    assert_eq!(frame.surface(120, 118), Surface::Wall(1));
    // Sprite column 0 is empty: columns 110 and 111 (`u = 0`) show the wall.
    assert_eq!(frame.surface(110, 120), Surface::Wall(1));
    assert_eq!(frame.surface(112, 120), Surface::Thing(0));
    assert_eq!(frame.thing_sectors, vec![0]);
    assert_eq!(frame.sector_of(Surface::Thing(0)), Some(0));
}

/// A solid sprite standing with `z = 24` (heights `[24, 40]`) at depth `THING_DEPTH_MIN = 4`
/// fills the screen: `u = floor(m·4 + 4)` with `|m| < 1`, `v = floor(8 + k·4)` with `|k| < 2/3`.
/// A 1/256 unit nearer, behind the eye, or beside it (`z' = 0`) it is not drawn at all.
#[test]
fn things_behind_the_eye_or_nearer_than_the_minimum_depth_are_not_drawn() {
    let fixture = Fixture::new(200);
    let bare = room(64, NO_PORTAL);
    let behind = fixture.render(&bare.tables(), &centre_camera(), &view(Lighting::Off));
    let at = |x: f64, y: f64| {
        let map = room(64, NO_PORTAL).with_things(vec![thing(x, y, 0, SOLID_SPRITE, 24, 0)]);
        fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Off))
    };
    let nearest = f64::from(THING_DEPTH_MIN);
    let frame = at(nearest, 0.0);
    assert!(frame.surfaces.iter().all(|&s| s == Surface::Thing(0)));
    assert!(frame.depths.iter().all(|&d| d == nearest));
    // Column 0: `u = floor(−119.5/120·4 + 4) = 0`; row 0: `v = floor(8 − 79.5/120·4) = 5`.
    assert_eq!(frame.index(0, 0), solid(0, 5));
    for (x, y) in [(nearest - 1.0 / 256.0, 0.0), (-32.0, 0.0), (0.0, 20.0)] {
        let frame = at(x, y);
        assert_eq!(frame.surfaces, behind.surfaces, "thing at ({x}, {y})");
        assert_eq!(frame.indices, behind.indices, "thing at ({x}, {y})");
    }
}

/// A solid sprite standing on room B's floor (20; B's ceiling 44) at (128, 0), depth 128,
/// heights `[20, 36]`: column 120 meets it at `u = floor(128/240 + 4) = 4`, row `y` at
/// `v = floor(36 − eye_z + (y + ½ − 80)·128/120)`. A pixel shows it exactly where it is in the
/// image and the frame without it shows a surface of B there (the ray reached B).
/// - Eye at 10: the thing is rows 56..=70 (`v = floor((16y − 882)/15)`), but the lower strip
///   (`h(64) ≤ 20`: `y + ½ ≥ 61.25`) covers rows 61..: rows 56..=60 show it.
/// - Eye at 54: rows 97..=111 (`v = floor((16y − 1542)/15)`), the upper strip (`h(64) > 44`:
///   `y + ½ < 98.75`) covers rows ..=98: rows 99..=111 show it.
#[test]
fn a_thing_beyond_a_portal_is_cut_by_the_strips() {
    let fixture = Fixture::new(200);
    let bare = two_rooms(20, 44, CEIL_TEX, CEIL_TEX, 200);
    let map = two_rooms(20, 44, CEIL_TEX, CEIL_TEX, 200).with_things(vec![thing(
        128.0,
        0.0,
        1,
        SOLID_SPRITE,
        0,
        0,
    )]);
    for (eye_z, rows, strip, cut_row) in [
        (10.0, 56..=60, Surface::Lower(1), 61),
        (54.0, 99..=111, Surface::Upper(1), 98),
    ] {
        let camera = Camera {
            eye_z,
            ..centre_camera()
        };
        let lighting = Lighting::Sector;
        let behind = fixture.render(&bare.tables(), &camera, &view(lighting));
        let frame = fixture.render(&map.tables(), &camera, &view(lighting));
        let (mut shown, mut cut) = (0, 0);
        for y in 0..160i32 {
            for x in 0..240i32 {
                let u = (16 * x - 1852).div_euclid(15);
                let v = (15 * (36 - eye_z as i32) + 16 * y - 1272).div_euclid(15);
                let (xs, ys) = (x as usize, y as usize);
                let covered = (0..8).contains(&u) && (0..16).contains(&v);
                let reached = behind.sector_of(behind.surface(xs, ys)) == Some(1);
                let expected = if covered && reached {
                    shown += 1;
                    let texel = solid(u as usize, v as usize);
                    let row = light_row(200, 128, lighting).unwrap();
                    (Surface::Thing(0), fixture.colormap[row][usize::from(texel)])
                } else {
                    cut += usize::from(covered);
                    (behind.surface(xs, ys), behind.index(xs, ys))
                };
                let got = (frame.surface(xs, ys), frame.index(xs, ys));
                assert_eq!(got, expected, "eye {eye_z}: ({x}, {y})");
            }
        }
        assert!(
            shown > 20 && cut > 10,
            "eye {eye_z}: {shown} shown, {cut} cut"
        );
        for y in 0..160 {
            let expected = if rows.contains(&y) {
                Surface::Thing(0)
            } else {
                behind.surface(120, y)
            };
            assert_eq!(frame.surface(120, y), expected, "eye {eye_z}: row {y}");
        }
        assert_eq!(frame.surface(120, cut_row), strip, "eye {eye_z}");
    }
}

/// Room B extended north, `x ∈ [64, 192]`, `y ∈ [−96, 32]` (walls 4..=8; 7 the portal back, 8
/// the solid stretch `(64,−32)→(64,−96)`), and a thing in its north part at (80, −63). The eye at
/// (60, −28), looking 100° from +x toward −y (binary angle 65536 − 18204): the thing is 40° right of the view
/// direction, on screen, but every ray of the view (45° either side) meets A's north wall within
/// 4 units of going north, before `x = 64`: the portal is out of view, so the thing is not drawn.
#[test]
fn a_thing_whose_portal_is_out_of_view_is_not_drawn() {
    let build = |things: Vec<Thing>| {
        let mut map = room(64, 1);
        map.vertices.extend([
            Vertex { x: 64, y: -96 },
            Vertex { x: 192, y: -96 },
            Vertex { x: 192, y: 32 },
        ]);
        map.walls.extend([
            wall(4, 5, NO_PORTAL),
            wall(5, 6, NO_PORTAL),
            wall(6, 2, NO_PORTAL),
            wall(2, 1, 0),
            wall(1, 4, NO_PORTAL),
        ]);
        map.sectors.push(Sector {
            wall_count: 5,
            ..sector(4, 0, 64, CEIL_TEX, 200)
        });
        map.with_things(things)
    };
    let camera = Camera {
        x: 60.0,
        y: -28.0,
        angle: angle_from_bits(47332),
        ..centre_camera()
    };
    let fixture = Fixture::new(200);
    let placed = thing(80.0, -63.0, 1, SOLID_SPRITE, 8, 0);
    // The thing is in view: its centre's column is on screen, in front of the eye.
    let (sin, cos) = camera.angle.sin_cos();
    let (dx, dy) = (80.0 - camera.x, -63.0 - camera.y);
    let (across, depth) = (dx * -sin + dy * cos, dx * cos + dy * sin);
    let centre_column = 120.0 + 120.0 * across / depth;
    assert!(depth > 20.0 && (150.0..235.0).contains(&centre_column));

    let frame = fixture.render(&build(vec![placed]).tables(), &camera, &view(Lighting::Off));
    let behind = fixture.render(&build(Vec::new()).tables(), &camera, &view(Lighting::Off));
    assert_eq!(frame.surfaces, behind.surfaces);
    assert_eq!(frame.indices, behind.indices);
    assert!(!frame.surfaces.contains(&Surface::Thing(0)));
    assert_eq!(frame.thing_sectors, vec![1]);
}

/// Two solid sprites standing with `z = 8`. At depth 40 on the centre line a sprite is columns
/// 108..=131, rows 104..=151 (`v = floor((y + ½ − 80)/3 − 8)`); at depth 48 columns 110..=129,
/// rows 100..=139. The nearer shows where both do, whatever their order in the table; at equal
/// depth the later in the table does. At depth 48 with `x' = 2` a sprite covers `[−2, 6)`
/// across: columns 115..=134 (`2c − 239 ∈ [−10, 30)`), so columns 110..=114 see only the one on
/// the centre line and 130..=134 only the other.
#[test]
fn the_nearer_of_two_overlapping_things_shows() {
    let fixture = Fixture::new(200);
    let at = |things: Vec<Thing>| {
        let map = room(64, NO_PORTAL).with_things(things);
        fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Off))
    };
    let far = thing(48.0, 0.0, 0, SOLID_SPRITE, 8, 0);
    let near = thing(40.0, 0.0, 0, SOLID_SPRITE, 8, 0);
    let frame = at(vec![far, near]);
    assert_eq!(frame.surface(120, 120), Surface::Thing(1));
    assert_eq!(frame.depth(120, 120), 40.0);
    // `v = floor(40.5/3 − 8) = 5`.
    assert_eq!(frame.index(120, 120), solid(4, 5));
    assert_eq!(frame.surface(120, 101), Surface::Thing(0));
    assert_eq!(frame.surface(120, 145), Surface::Thing(1));
    let frame = at(vec![near, far]);
    assert_eq!(frame.surface(120, 120), Surface::Thing(0));
    assert_eq!(frame.surface(120, 101), Surface::Thing(1));

    let beside = thing(48.0, 2.0, 0, SOLID_SPRITE, 8, 0);
    let frame = at(vec![far, beside]);
    assert_eq!(
        [112, 120, 132].map(|x| frame.surface(x, 120)),
        [Surface::Thing(0), Surface::Thing(1), Surface::Thing(1)]
    );
    let frame = at(vec![beside, far]);
    assert_eq!(
        [112, 120, 132].map(|x| frame.surface(x, 120)),
        [Surface::Thing(1), Surface::Thing(1), Surface::Thing(0)]
    );
}

/// A solid sprite hanging `z = 8` below room A's ceiling (64) at depth 48: top at 56, bottom at
/// 40, `v = floor(56 − 32 + (y + ½ − 80)·48/120)`: rows 20..=59 of column 120, where the wall
/// shows without it; row 20 is `v = floor(24 − 23.8) = 0`.
#[test]
fn a_hanging_thing_hangs_its_top_at_ceiling_minus_z() {
    let map =
        room(64, NO_PORTAL).with_things(vec![thing(48.0, 0.0, 0, SOLID_SPRITE, 8, THING_HANGING)]);
    let fixture = Fixture::new(200);
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Off));
    assert_eq!(
        runs(&frame, 120),
        vec![
            (0, 19, Surface::Ceiling(0)),
            (20, 59, Surface::Thing(0)),
            (60, 139, Surface::Wall(1)),
            (140, 159, Surface::Floor(0))
        ]
    );
    assert_eq!(frame.index(120, 20), solid(4, 0));
    assert_eq!(frame.index(120, 59), solid(4, 15));
}

/// A set's image follows the tick (`floor(tick / frame_ticks) mod frames`) and the side the
/// eye sees (rotation `r`: the thing seen from its facing plus `r`·45°).
#[test]
fn a_set_shows_the_frame_of_the_tick_and_the_rotation_of_the_eye() {
    let mut fixture = Fixture::new(200);
    // Images 2.. are solid, each one index: 8 rotations (set 0), then two frames (set 1).
    fixture.sprites.truncate(2);
    for image in 0..10u8 {
        fixture
            .sprites
            .push(OwnedSprite::new(8, 16, move |_, _| Some(100 + image)));
    }
    let sets = [
        SpriteSet {
            name: "rotating",
            first: 2,
            frames: 1,
            rotations: 8,
        },
        SpriteSet {
            name: "animated",
            first: 10,
            frames: 2,
            rotations: 1,
        },
    ];
    let shown = |set: u16, facing: u16, tick: u32| {
        let mut thing = thing(48.0, 0.0, 0, set, 8, 0);
        thing.angle = facing;
        thing.frame_ticks = 4;
        let map = room(64, NO_PORTAL).with_things(vec![thing]);
        let view = View {
            tick,
            ..view(Lighting::Off)
        };
        let frame = fixture.render_with_sets(&map.tables(), &centre_camera(), &view, &sets);
        assert_eq!(frame.surface(120, 110), Surface::Thing(0));
        frame.index(120, 110)
    };
    // The eye is west of the thing: facing east it sees the back (r4), facing south (a quarter
    // turn on) r2, facing west the front (r0), facing north r6; between, the diagonals.
    assert_eq!(shown(0, 0, 0), 100 + 4);
    assert_eq!(shown(0, 16384, 0), 100 + 2);
    assert_eq!(shown(0, 32768, 0), 100);
    assert_eq!(shown(0, 49152, 0), 100 + 6);
    assert_eq!(shown(0, 8192, 0), 100 + 3);
    // Four ticks a frame, two frames.
    assert_eq!(shown(1, 0, 3), 108);
    assert_eq!(shown(1, 0, 4), 109);
    assert_eq!(shown(1, 0, 8), 108);
}

// ---------------------------------------------------------------------------------------------
// Portal middles and translucency
//
// Rooms A and B with B's floor 0 and ceiling 48 (light 200): A's wall 1 is the portal, with the
// grate as its middle, x offset 5, y offset 2. Columns 60..=179 see the portal (`|m| < ½`), at
// `t = 64` exactly, `y = 64·m`, so `u = floor(32 + 64·m + 5) = floor((8c − 401)/15) mod 8`. The
// image's top is the lower ceiling plus the offset, 50: row `y` (`h(64) = 32 − (8y − 636)/15`)
// meets it at `v = floor(50 − h) = floor((8y − 366)/15)`, rows 46..=90 of the image, but the
// upper strip (`h(64) > 48`) covers rows ..=49: in column 120, `u = 5`, rows 50..=90 are
// `v = 2..=23`.

/// The middles' two rooms, with the grate on wall 1 (with `flags`).
fn grated_rooms(flags: u16) -> OwnedMap {
    let mut map = two_rooms(0, 48, CEIL_TEX, CEIL_TEX, 200);
    map.walls[1].middle = GRATE_SPRITE;
    map.walls[1].x_offset = 5;
    map.walls[1].y_offset = 2;
    map.walls[1].flags = flags;
    map
}

/// The two rooms without the grate (wall 1 keeps its offsets: they only move its strips).
fn bare_rooms() -> OwnedMap {
    let mut map = grated_rooms(0);
    map.walls[1].middle = NO_TEXTURE;
    map
}

/// The grate's texel at pixel `(x, y)` of the centre camera's view, if the pixel's ray meets
/// the grate's image at an opaque texel (whether it reaches the portal or not).
fn grate_at(x: i32, y: i32) -> Option<u8> {
    let (u, v) = ((8 * x - 401).div_euclid(15), (8 * y - 366).div_euclid(15));
    ((60..180).contains(&x) && (0..24).contains(&v))
        .then(|| grate(u.rem_euclid(8) as usize, v as usize))
        .flatten()
}

/// Every pixel whose ray passes the portal (the frame without the grate shows room B there) and
/// meets an opaque texel of the grate shows `Middle(1)` at that texel, lit by room A's light at
/// depth 64, at depth 64; the grate's holes, and every pixel whose ray stops in A, are as
/// without it.
#[test]
fn a_middle_shows_its_opaque_texels_in_the_opening_and_the_room_behind_through_its_holes() {
    let fixture = Fixture::new(200);
    let lighting = Lighting::SectorDepth;
    let behind = fixture.render(&bare_rooms().tables(), &centre_camera(), &view(lighting));
    let frame = fixture.render(&grated_rooms(0).tables(), &centre_camera(), &view(lighting));
    let row = light_row(128, 64, lighting).unwrap();

    let (mut shown, mut holes, mut cut) = (0, 0, 0);
    for y in 0..160i32 {
        for x in 0..240i32 {
            let (xs, ys) = (x as usize, y as usize);
            let reached = behind.sector_of(behind.surface(xs, ys)) == Some(1);
            let got = frame.pixel(xs, ys);
            match grate_at(x, y) {
                Some(texel) if reached => {
                    shown += 1;
                    let index = fixture.colormap[row][usize::from(texel)];
                    assert_eq!(got, (Surface::Middle(1), index, 64.0), "({x}, {y})");
                    continue;
                }
                Some(_) => cut += 1,
                None => {
                    let v = (8 * y - 366).div_euclid(15);
                    holes += usize::from(reached && (0..24).contains(&v));
                }
            }
            let expected = behind.pixel(xs, ys);
            assert_eq!(got, expected, "({x}, {y})");
        }
    }
    assert!(
        shown > 2000 && holes > 500 && cut > 200,
        "{shown} shown, {holes} holes, {cut} cut"
    );
    // Column 120: the upper strip down to row 49 (the image's rows 0 and 1 behind it), the grate
    // from row 50 (`v = 2`) to row 90 (rows 89 and 90 are `v = 23`, a transparent row: B's
    // wall 5 shows).
    assert_eq!(frame.surface(120, 49), Surface::Upper(1));
    assert_eq!(
        frame.index(120, 50),
        fixture.colormap[row][usize::from(grate(5, 2).unwrap())]
    );
    assert_eq!(frame.surface(120, 88), Surface::Middle(1));
    assert_eq!(frame.surface(120, 89), Surface::Wall(5));
    assert_eq!(frame.surface(120, 90), Surface::Wall(5));
    assert_eq!(frame.surface(120, 91), Surface::Wall(5));
    // Column 116: `u = floor(527/15) = 35` → 3, a transparent column.
    assert_eq!(frame.surface(116, 70), behind.surface(116, 70));
    assert_eq!(frame.sector_of(Surface::Middle(1)), Some(0));
}

/// A solid sprite in room A at (48, −8), `z = 24` (depth 48, heights `[24, 40]`): columns
/// 90..=109 (`u = floor((2c − 179)/5)`), rows 60..=99 (`v = floor((2y − 119)/5)`), in front of
/// the grate, covers it. A solid sprite in room B at (128, 0), `z = 16` (depth 128, heights
/// `[16, 32]`): columns 116..=123 (`u = floor((16c − 1852)/15)`), rows 80..=94
/// (`v = floor((16y − 1272)/15)`), behind it, shows only through its holes (columns 116 and 117
/// are `u = 3`, rows 89 and 90 `v = 23`) and below it. Lighting off.
#[test]
fn a_thing_before_the_portal_covers_the_middle_and_one_beyond_is_covered_by_it() {
    let fixture = Fixture::new(200);
    let near = thing(48.0, -8.0, 0, SOLID_SPRITE, 24, 0);
    let far = thing(128.0, 0.0, 1, SOLID_SPRITE, 16, 0);
    let lighting = Lighting::Off;
    let behind = fixture.render(&bare_rooms().tables(), &centre_camera(), &view(lighting));
    let map = grated_rooms(0).with_things(vec![near, far]);
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(lighting));

    let (mut near_over, mut far_under, mut far_through) = (0, 0, 0);
    for y in 0..160i32 {
        for x in 0..240i32 {
            let (xs, ys) = (x as usize, y as usize);
            let reached = behind.sector_of(behind.surface(xs, ys)) == Some(1);
            let (near_u, near_v) = ((2 * x - 179).div_euclid(5), (2 * y - 119).div_euclid(5));
            let (far_u, far_v) = (
                (16 * x - 1852).div_euclid(15),
                (16 * y - 1272).div_euclid(15),
            );
            let near_covers = (0..8).contains(&near_u) && (0..16).contains(&near_v);
            let far_covers = reached && (0..8).contains(&far_u) && (0..16).contains(&far_v);
            let middle = grate_at(x, y).filter(|_| reached);
            let expected = if near_covers {
                near_over += usize::from(middle.is_some());
                let texel = solid(near_u as usize, near_v as usize);
                (Surface::Thing(0), texel, 48.0)
            } else if let Some(texel) = middle {
                far_under += usize::from(far_covers);
                (Surface::Middle(1), texel, 64.0)
            } else if far_covers {
                far_through += usize::from((0..24).contains(&(8 * y - 366).div_euclid(15)));
                let texel = solid(far_u as usize, far_v as usize);
                (Surface::Thing(1), texel, 128.0)
            } else {
                behind.pixel(xs, ys)
            };
            let got = frame.pixel(xs, ys);
            assert_eq!(got, expected, "({x}, {y})");
        }
    }
    assert!(
        near_over > 250 && far_under > 40 && far_through > 15,
        "{near_over} over, {far_under} under, {far_through} through"
    );
    assert_eq!(frame.surface(100, 70), Surface::Thing(0));
    assert_eq!(frame.surface(120, 85), Surface::Middle(1));
    assert_eq!(frame.surface(116, 85), Surface::Thing(1));
    assert_eq!(frame.surface(120, 88), Surface::Middle(1));
    assert_eq!(frame.surface(120, 89), Surface::Thing(1));
    assert_eq!(frame.surface(120, 91), Surface::Thing(1));
}

/// At equal depth a thing of the portal's own sector covers the middle and one of the sector
/// behind is covered (the engine draws a sector's middles before its things, after those of
/// the sectors behind). A solid sprite at (64, −8), `z = 24`, depth 64 as the portal: at
/// (105, 70) it is texel `(floor(−14.5·64/120 + 12), floor(8 − 9.5·64/120)) = (4, 2)`, over the
/// grate's `(floor(439/15) mod 8, floor(194/15)) = (5, 12)`, opaque.
#[test]
fn at_equal_depth_a_middle_is_behind_its_sectors_things_and_before_the_next() {
    let fixture = Fixture::new(200);
    let shown = |sector: u16| {
        let map = grated_rooms(0).with_things(vec![thing(64.0, -8.0, sector, SOLID_SPRITE, 24, 0)]);
        let frame = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Off));
        frame.pixel(105, 70)
    };
    assert_eq!(shown(0), (Surface::Thing(0), solid(4, 2), 64.0));
    assert_eq!(shown(1), (Surface::Middle(1), grate(5, 12).unwrap(), 64.0));
}

/// A translucent grate shows `blend[behind][front]` with `front` its lit texel and `behind` the
/// pixel without it; a translucent solid sprite in front of it (at (48, −8), `z = 24`, as above)
/// blends over that in turn: `blend[blend[behind][grate]][sprite]`. The surface and the depth
/// are the nearest's. Without a blend table both are drawn opaque.
#[test]
fn a_translucent_middle_blends_over_the_room_behind_and_under_a_translucent_thing() {
    let mut fixture = Fixture::new(200);
    let lighting = Lighting::SectorDepth;
    let near = thing(48.0, -8.0, 0, SOLID_SPRITE, 24, THING_TRANSLUCENT);
    let translucent = grated_rooms(WALL_MIDDLE_TRANSLUCENT).with_things(vec![near]);
    let opaque = grated_rooms(0).with_things(vec![Thing { flags: 0, ..near }]);
    let unblended = fixture.render(&translucent.tables(), &centre_camera(), &view(lighting));
    let drawn_opaque = fixture.render(&opaque.tables(), &centre_camera(), &view(lighting));
    assert_eq!(unblended, drawn_opaque);

    fixture.blend = Some(blend_table());
    let behind = fixture.render(&bare_rooms().tables(), &centre_camera(), &view(lighting));
    let frame = fixture.render(&translucent.tables(), &centre_camera(), &view(lighting));
    let (grate_row, thing_row) = (
        light_row(128, 64, lighting).unwrap(),
        light_row(128, 48, lighting).unwrap(),
    );
    let cm = &fixture.colormap;
    let (mut middles, mut both, mut things) = (0, 0, 0);
    for y in 0..160i32 {
        for x in 0..240i32 {
            let (xs, ys) = (x as usize, y as usize);
            let reached = behind.sector_of(behind.surface(xs, ys)) == Some(1);
            let mut expected = behind.pixel(xs, ys);
            let middle = grate_at(x, y).filter(|_| reached);
            if let Some(texel) = middle {
                middles += 1;
                let front = cm[grate_row][usize::from(texel)];
                expected = (Surface::Middle(1), blended(expected.1, front), 64.0);
            }
            let (u, v) = ((2 * x - 179).div_euclid(5), (2 * y - 119).div_euclid(5));
            if (0..8).contains(&u) && (0..16).contains(&v) {
                things += 1;
                both += usize::from(middle.is_some());
                let front = cm[thing_row][usize::from(solid(u as usize, v as usize))];
                expected = (Surface::Thing(0), blended(expected.1, front), 48.0);
            }
            let got = frame.pixel(xs, ys);
            assert_eq!(got, expected, "({x}, {y})");
        }
    }
    assert!(
        middles > 2000 && both > 250 && things > both + 300,
        "{middles} middles, {both} both, {things} things"
    );
    // (120, 50): the grate's (5, 2) over B's ceiling.
    assert_eq!(behind.surface(120, 50), Surface::Ceiling(1));
    assert_eq!(
        frame.index(120, 50),
        blended(
            behind.index(120, 50),
            cm[grate_row][usize::from(grate(5, 2).unwrap())]
        )
    );
}

/// A translucent holed sprite over room A's wall 1 (the set-up of
/// `a_thing_shows_its_opaque_texels_and_the_wall_through_its_holes`): its opaque texels show
/// `blend[wall][sprite]`, its holes the wall; without a blend table it is drawn opaque.
#[test]
fn a_translucent_thing_blends_over_the_wall() {
    let mut fixture = Fixture::new(200);
    let lighting = Lighting::SectorDepth;
    let placed = thing(48.0, 0.0, 0, HOLED_SPRITE, 8, THING_TRANSLUCENT);
    let bare = room(64, NO_PORTAL);
    let map = room(64, NO_PORTAL).with_things(vec![placed]);
    let opaque = room(64, NO_PORTAL).with_things(vec![Thing { flags: 0, ..placed }]);
    let drawn_opaque = fixture.render(&opaque.tables(), &centre_camera(), &view(lighting));
    assert_eq!(
        fixture.render(&map.tables(), &centre_camera(), &view(lighting)),
        drawn_opaque
    );

    fixture.blend = Some(blend_table());
    let behind = fixture.render(&bare.tables(), &centre_camera(), &view(lighting));
    let frame = fixture.render(&map.tables(), &centre_camera(), &view(lighting));
    let row = light_row(128, 48, lighting).unwrap();
    let mut shown = 0;
    for y in 0..160usize {
        for x in 0..240usize {
            let expected = if drawn_opaque.surface(x, y) == Surface::Thing(0) {
                shown += 1;
                let (u, v) = (
                    (2 * x as i32 - 219).div_euclid(5),
                    (2 * y as i32 - 199).div_euclid(5),
                );
                let texel = holed(u as usize, v as usize).unwrap();
                let front = fixture.colormap[row][usize::from(texel)];
                assert_eq!(drawn_opaque.index(x, y), front, "({x}, {y})");
                (Surface::Thing(0), blended(behind.index(x, y), front), 48.0)
            } else {
                behind.pixel(x, y)
            };
            let got = frame.pixel(x, y);
            assert_eq!(got, expected, "({x}, {y})");
        }
    }
    assert!(shown > 300, "{shown} shown");
    assert_eq!(behind.surface(120, 120), Surface::Wall(1));
}

/// A middle is drawn only where a ray passes its portal. The layout of
/// `a_thing_whose_portal_is_out_of_view_is_not_drawn` with the grate on A's wall 1 (the portal is
/// out of view), and the two rooms with B closed (floor and ceiling 40, a shut door: every ray
/// at the portal meets a strip, while the grate's rows are in view): both frames are as without
/// the grate.
#[test]
fn a_middle_whose_portal_no_ray_passes_is_not_drawn() {
    let fixture = Fixture::new(200);
    let out_of_view = |middle: u16| {
        let mut map = room(64, 1);
        map.walls[1].middle = middle;
        map.vertices.extend([
            Vertex { x: 64, y: -96 },
            Vertex { x: 192, y: -96 },
            Vertex { x: 192, y: 32 },
        ]);
        map.walls.extend([
            wall(4, 5, NO_PORTAL),
            wall(5, 6, NO_PORTAL),
            wall(6, 2, NO_PORTAL),
            wall(2, 1, 0),
            wall(1, 4, NO_PORTAL),
        ]);
        map.sectors.push(Sector {
            wall_count: 5,
            ..sector(4, 0, 64, CEIL_TEX, 200)
        });
        map
    };
    let camera = Camera {
        x: 60.0,
        y: -28.0,
        angle: angle_from_bits(47332),
        ..centre_camera()
    };
    let frame = fixture.render(
        &out_of_view(GRATE_SPRITE).tables(),
        &camera,
        &view(Lighting::Off),
    );
    let behind = fixture.render(
        &out_of_view(NO_TEXTURE).tables(),
        &camera,
        &view(Lighting::Off),
    );
    assert_eq!(frame, behind);

    let closed = |middle: u16| {
        let mut map = two_rooms(40, 40, CEIL_TEX, CEIL_TEX, 200);
        map.walls[1].middle = middle;
        map
    };
    let frame = fixture.render(
        &closed(GRATE_SPRITE).tables(),
        &centre_camera(),
        &view(Lighting::Off),
    );
    let behind = fixture.render(
        &closed(NO_TEXTURE).tables(),
        &centre_camera(),
        &view(Lighting::Off),
    );
    assert_eq!(frame, behind);
    assert!(!frame.surfaces.contains(&Surface::Middle(1)));
    // The grate's rows `h ∈ (16, 40]` at the portal are on screen, on the lower strip.
    assert_eq!(frame.surface(120, 90), Surface::Lower(1));
}

/// Middles are the only surfaces drawn cyan in the diff picture: red below 96, green and blue at
/// least 160.
#[test]
fn middles_have_their_own_colours() {
    use Surface::*;
    let cyan = |s: Surface| {
        let [r, g, b] = surface_colour(s);
        r < 96 && g >= 160 && b >= 160
    };
    for i in 0..200 {
        assert!(cyan(Middle(i)), "middle {i}");
        for other in [Wall(i), Upper(i), Lower(i), Floor(i), Ceiling(i), Thing(i)] {
            assert!(!cyan(other), "{other:?}");
        }
    }
    assert!(!cyan(Sky) && !cyan(None));
    assert_ne!(surface_colour(Middle(0)), surface_colour(Middle(1)));
    assert_ne!(surface_colour(Middle(1)), surface_colour(Wall(1)));
}

// ---------------------------------------------------------------------------------------------
// Sectors and poses

#[test]
fn find_sector_is_strict() {
    let map = two_rooms(16, 48, CEIL_TEX, CEIL_TEX, 200);
    let map = map.tables();
    assert_eq!(find_sector(&map, 0.0, 0.0), Some(0));
    assert_eq!(find_sector(&map, 63.999, 31.999), Some(0));
    assert_eq!(find_sector(&map, 64.001, 0.0), Some(1));
    assert_eq!(find_sector(&map, 191.5, -31.5), Some(1));
    // On the shared portal, on an outer wall, on a vertex, outside.
    assert_eq!(find_sector(&map, 64.0, 0.0), None);
    assert_eq!(find_sector(&map, -64.0, 10.0), None);
    assert_eq!(find_sector(&map, 0.0, 32.0), None);
    assert_eq!(find_sector(&map, 64.0, 32.0), None);
    assert_eq!(find_sector(&map, 300.0, 0.0), None);
}

/// Without a sector the camera's is found; on a wall line there is none and the frame is all
/// holes.
#[test]
fn render_finds_the_camera_sector() {
    let map = two_rooms(16, 48, CEIL_TEX, CEIL_TEX, 200);
    let fixture = Fixture::new(200);
    let known = fixture.render(&map.tables(), &centre_camera(), &view(Lighting::Off));
    let found = fixture.render(
        &map.tables(),
        &Camera {
            sector: None,
            ..centre_camera()
        },
        &view(Lighting::Off),
    );
    assert_eq!(known, found);
    let on_portal = Camera {
        x: 64.0,
        sector: None,
        ..centre_camera()
    };
    let frame = fixture.render(&map.tables(), &on_portal, &view(Lighting::Off));
    assert!(frame.surfaces.iter().all(|&s| s == Surface::None));
}

/// Poses land strictly inside a sector, 2 units clear of its walls, at eye height
/// `min(floor + 32, ceil − 16)`: 32 in A (floor 0, ceiling 64), `min(48, 40) = 40` in B
/// (floor 16, ceiling 56); on the engine's grids; reproducible from the seed.
#[test]
fn sample_poses_are_valid_and_reproducible() {
    let owned = two_rooms(16, 56, CEIL_TEX, CEIL_TEX, 200);
    let map = owned.tables();
    let poses = sample_poses(&map, 64, 7);
    assert_eq!(poses.len(), 64);
    assert_eq!(poses, sample_poses(&map, 64, 7));
    assert_ne!(poses, sample_poses(&map, 64, 8));
    let mut sectors = BTreeSet::new();
    for pose in &poses {
        let sector = pose.sector.expect("poses carry their sector");
        sectors.insert(sector);
        assert_eq!(find_sector(&map, pose.x, pose.y), Some(sector));
        let (x0, x1) = if sector == 0 {
            (-64.0, 64.0)
        } else {
            (64.0, 192.0)
        };
        let clearance = (pose.x - x0)
            .min(x1 - pose.x)
            .min(pose.y + 32.0)
            .min(32.0 - pose.y);
        assert!(clearance >= 2.0, "{pose:?} within 2 of a wall");
        assert_eq!(pose.eye_z, if sector == 0 { 32.0 } else { 40.0 });
        assert_eq!((pose.x * 256.0).fract(), 0.0);
        assert_eq!((pose.y * 256.0).fract(), 0.0);
        assert_eq!(angle_from_bits(angle_to_bits(pose.angle)), pose.angle);
    }
    assert_eq!(sectors, BTreeSet::from([0, 1]));
}

#[test]
fn camera_from_fixed_is_exact() {
    let camera = Camera::from_fixed(-3 * 256 + 1, 512, 32 * 256, 16384, Some(2));
    assert_eq!(
        (camera.x, camera.y, camera.eye_z),
        (-3.0 + 1.0 / 256.0, 2.0, 32.0)
    );
    assert_eq!(camera.angle, std::f64::consts::FRAC_PI_2);
    assert_eq!(camera.angle_bits(), 16384);
}

// ---------------------------------------------------------------------------------------------
// Comparison

/// An oracle frame; walls 0..=3 belong to sector 0, 4..=7 to sector 1; things 0, 1, 2 to
/// sectors 0, 1, 2.
fn oracle_frame(surfaces: Vec<Surface>, width: usize, height: usize) -> Frame {
    Frame {
        width,
        height,
        indices: vec![10; surfaces.len()],
        depths: vec![1.0; surfaces.len()],
        surfaces,
        wall_sectors: vec![0, 0, 0, 0, 1, 1, 1, 1],
        thing_sectors: vec![0, 1, 2],
        plane_groups: Vec::new(),
    }
}

/// Oracle                      Engine
/// C0 C0 C1 C1                 C0* C0 C0 C1        (* index 11 instead of 10)
/// W1 W1 W5 W5                 W1  W1 W1 --
/// F0 F0 F0 Sky                F0  F0 F0 F0
/// Surface mismatches: (2,0) C0 for C1, (2,1) W1 for W5, (3,1) hole, (3,2) F0 for the sky: 4 of
/// 12. Texel mismatches: (0,0) only (the engine's index at (2,0) differs too, but that pixel
/// already is a surface mismatch). Edge error: C0, W1 and F0 are each 1 pixel from where the
/// oracle draws them; the hole does not count (no oracle pixel is a hole, it would be
/// `max(4, 3) = 4`). Sectors: both frames show 0 and 1.
#[test]
fn compare_counts_mismatches_holes_and_edge_error() {
    use Surface::*;
    let oracle = oracle_frame(
        vec![
            Ceiling(0),
            Ceiling(0),
            Ceiling(1),
            Ceiling(1),
            Wall(1),
            Wall(1),
            Wall(5),
            Wall(5),
            Floor(0),
            Floor(0),
            Floor(0),
            Sky,
        ],
        4,
        3,
    );
    let engine = [
        Ceiling(0),
        Ceiling(0),
        Ceiling(0),
        Ceiling(1),
        Wall(1),
        Wall(1),
        Wall(1),
        None,
        Floor(0),
        Floor(0),
        Floor(0),
        Floor(0),
    ];
    let mut indices = [10u8; 12];
    indices[0] = 11;
    indices[2] = 12;
    let result = compare(&engine, &indices, &oracle);
    assert_eq!(result.pixels, 12);
    assert_eq!(result.surface_mismatches, 4);
    assert_eq!(result.texel_mismatches, 1);
    assert_eq!(result.holes, 1);
    assert_eq!(result.max_edge_error_px, 1);
    assert!(result.missed_sectors.is_empty() && result.extra_sectors.is_empty());
    assert!((result.surface_mismatch_percent() - 100.0 * 4.0 / 12.0).abs() < 1e-12);
    assert!((result.texel_mismatch_percent() - 100.0 / 12.0).abs() < 1e-12);
}

/// One row: the oracle's edge between walls 0 and 1 is at x = 2, the engine's at x = 4, so
/// pixels 2 and 3 are mismatched, 1 and 2 pixels from the oracle's wall 0: error 2.
#[test]
fn compare_measures_edge_displacement() {
    use Surface::*;
    let oracle = oracle_frame(vec![Wall(0), Wall(0), Wall(1), Wall(1), Wall(1)], 5, 1);
    let engine = [Wall(0), Wall(0), Wall(0), Wall(0), Wall(1)];
    let result = compare(&engine, &[10; 5], &oracle);
    assert_eq!(
        (
            result.surface_mismatches,
            result.max_edge_error_px,
            result.holes
        ),
        (2, 2, 0)
    );

    let result = compare(&oracle.surfaces, &[10; 5], &oracle);
    assert_eq!(
        result,
        portalcast_oracle::Comparison {
            pixels: 5,
            ..Default::default()
        }
    );
}

/// The oracle shows sectors 0 (floor) and 1 (wall 6 is sector 1's); the engine shows 0
/// (wall 2), 2 (its ceiling) and wall 9, which is no sector's: missed [1], extra [2]. None of
/// the engine's surfaces is in the oracle frame: edge error `max(3, 1) = 3`.
#[test]
fn compare_lists_missed_and_extra_sectors() {
    use Surface::*;
    let oracle = oracle_frame(vec![Floor(0), Wall(6), Sky], 3, 1);
    let engine = [Wall(2), Ceiling(2), Wall(9)];
    let result = compare(&engine, &[10; 3], &oracle);
    assert_eq!(result.missed_sectors, vec![1]);
    assert_eq!(result.extra_sectors, vec![2]);
    assert_eq!(
        (result.surface_mismatches, result.max_edge_error_px),
        (3, 3)
    );
}

/// Things 0, 1, 2 belong to sectors 0, 1, 2. The oracle shows things 0 and 1, the engine things
/// 0 and 2: missed thing [1], extra thing [2]. A thing's pixels are its sector's: the engine
/// shows sector 2 only through thing 2 (extra), and sector 1 through wall 6 (not missed).
#[test]
fn compare_lists_missed_and_extra_things() {
    use Surface::*;
    let oracle = oracle_frame(vec![Thing(0), Thing(1), Thing(1), Floor(0), Wall(6)], 5, 1);
    let engine = [Thing(0), Floor(0), Floor(0), Thing(2), Wall(6)];
    let result = compare(&engine, &[10; 5], &oracle);
    assert_eq!(result.missed_things, vec![1]);
    assert_eq!(result.extra_things, vec![2]);
    assert!(result.missed_sectors.is_empty());
    assert_eq!(result.extra_sectors, vec![2]);
    assert_eq!(oracle.sector_of(Thing(1)), Some(1));
    assert_eq!(oracle.sector_of(Thing(3)), Option::None);

    // Thing 1 alone in sector 1 takes the sector with it.
    let oracle = oracle_frame(vec![Thing(0), Thing(1), Thing(1), Floor(0)], 4, 1);
    let result = compare(&[Thing(0), Floor(0), Floor(0), Floor(0)], &[10; 4], &oracle);
    assert_eq!(
        (result.missed_things, result.missed_sectors),
        (vec![1], vec![1])
    );

    // A thing the oracle shows in one pixel only is a sub-texel detail, not missed
    // (`MISSED_THING_MIN_PIXELS`); its sector still is.
    assert_eq!(portalcast_oracle::MISSED_THING_MIN_PIXELS, 2);
    let oracle = oracle_frame(vec![Thing(0), Thing(1), Floor(0)], 3, 1);
    let result = compare(&[Thing(0), Floor(0), Floor(0)], &[10; 3], &oracle);
    assert_eq!(
        (result.missed_things, result.missed_sectors),
        (vec![], vec![1])
    );
}

/// With the rows moved, a thing (like a sector) the oracle loses in either moved frame is not
/// missed; one it keeps in both is.
#[test]
fn row_tolerance_forgives_things_lost_in_a_moved_frame() {
    use Surface::*;
    let frame = oracle_frame(vec![Thing(0), Thing(0), Thing(1), Thing(1), Floor(0)], 5, 1);
    let without_1 = oracle_frame(vec![Thing(0), Thing(0), Floor(0), Floor(0), Floor(0)], 5, 1);
    let engine = [Floor(0); 5];
    let result = compare_with_row_tolerance(&engine, &[10; 5], &frame, [&frame, &without_1]);
    assert_eq!(result.missed_things, vec![0]);
    assert!(result.missed_sectors.is_empty());
    let result = compare_with_row_tolerance(&engine, &[10; 5], &frame, [&frame, &frame]);
    assert_eq!(result.missed_things, vec![0, 1]);
    assert_eq!(result.missed_sectors, vec![1]);
}

/// Things are the only surfaces drawn with every channel at least 160 in the diff picture.
#[test]
fn things_have_their_own_colours() {
    use Surface::*;
    let bright = |s: Surface| surface_colour(s).iter().all(|&c| c >= 160);
    for i in 0..200 {
        assert!(bright(Thing(i)), "thing {i}");
        for other in [Wall(i), Upper(i), Lower(i), Floor(i), Ceiling(i), Middle(i)] {
            assert!(!bright(other), "{other:?}");
        }
    }
    assert!(!bright(Sky) && !bright(None));
    assert_ne!(surface_colour(Thing(0)), surface_colour(Thing(1)));
}

#[test]
fn diff_png_has_three_panels() {
    use Surface::*;
    let oracle = oracle_frame(vec![Floor(0), Wall(6), Sky], 3, 1);
    let path =
        std::env::temp_dir().join(format!("portalcast-oracle-diff-{}.png", std::process::id()));
    write_diff_png(&[Floor(0), None, Sky], &oracle, &path).unwrap();
    let image = image::open(&path).unwrap().to_rgb8();
    std::fs::remove_file(&path).unwrap();
    // 3 panels of 3 columns and 2 gaps of 4.
    assert_eq!(image.dimensions(), (17, 1));
    // Mask panel starts at 2·(3 + 4) = 14: match, hole, match.
    assert_eq!(image.get_pixel(14, 0).0, [0, 0, 0]);
    assert_eq!(image.get_pixel(15, 0).0, [255, 255, 0]);
    assert_eq!(image.get_pixel(16, 0).0, [0, 0, 0]);
    assert_eq!(
        image.get_pixel(7, 0).0,
        portalcast_oracle::surface_colour(Floor(0))
    );
}

/// Sectors 0 and 1 are one plane group, 2 another: where the oracle shows 0's floor, the
/// engine's floor labelled 1 is the same surface and 2's is not; and the sectors a frame shows
/// are counted by group (wall 4 is sector 1's).
#[test]
fn compare_counts_a_floor_or_a_ceiling_as_its_plane_group() {
    use Surface::*;
    let mut oracle = oracle_frame(vec![Floor(0), Floor(0), Ceiling(1), Wall(4)], 4, 1);
    oracle.plane_groups = vec![0, 0, 2];
    let engine = [Floor(1), Floor(2), Ceiling(0), Wall(4)];
    let result = compare(&engine, &[10; 4], &oracle);
    assert_eq!(result.surface_mismatches, 1);
    assert!(result.missed_sectors.is_empty());
    assert_eq!(result.extra_sectors, vec![2]);
}

/// The bench hall's eight cells share their floor, ceiling and light and are one group; the
/// dais in their middle, raised and brighter, is one of its own.
#[test]
fn the_bench_hall_s_cells_are_one_plane_group_and_its_dais_another() {
    let map = portalcast_rom::assets::MAPS
        .iter()
        .find(|map| map.name == "bench")
        .expect("the bench map");
    let groups = portalcast_oracle::plane_groups(map);
    // The map file's order: hall_nw, hall_n, hall_ne, hall_w, dais, hall_e, hall_sw, hall_s,
    // hall_se.
    for cell in [0, 1, 2, 3, 5, 6, 7, 8] {
        assert_eq!(groups[cell], 0, "cell {cell}");
    }
    assert_eq!(groups[4], 4);
    assert!(groups.iter().filter(|&&group| group == 0).count() == 8);
}
