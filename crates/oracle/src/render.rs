//! Per-pixel ray casting and the texture rules of `portalcast::render::surface`, in f64.

use portalcast::render::light::light_row;
use portalcast::render::surface::{Surface, THING_DEPTH_MIN};
use portalcast::render::walk::same_planes;
use portalcast_format::{
    MapTables, Plane, Sector, Sprite, Texture, Wall, NO_SLOPE, NO_TEXTURE, SKY, THING_HANGING,
    THING_TRANSLUCENT, TRANSPARENT, WALL_MIDDLE_TRANSLUCENT,
};

use crate::geometry::{exit_wall, find_sector, vertex, Vec2};
use crate::{Assets, Camera, Frame, View};

/// One sector crossed by a column's 2D ray, from the previous segment's `t_out` (0 for the
/// first) to its own.
#[derive(Clone, Copy, Debug)]
struct Segment {
    sector: u16,
    t_out: f64,
    wall: u16,
    /// Position of the exit along the wall (0 at its start vertex, 1 at its end).
    s: f64,
}

/// What the ray of one pixel hits.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Hit {
    Sky,
    /// A floor or ceiling of `sector`, reached at depth `t`.
    Flat {
        surface: Surface,
        sector: u16,
        texture: u16,
        t: f64,
    },
    /// A wall or strip seen from `sector`, with its level-0 texture coordinates.
    Wall {
        surface: Surface,
        sector: u16,
        texture: u16,
        t: f64,
        u: f64,
        v: f64,
    },
    None,
}

/// A thing of the map as one frame sees it, worked out once per frame.
#[derive(Clone, Copy, Debug)]
struct ThingView<'a> {
    /// Index in the map's things table.
    index: u16,
    /// The sector whose group of things holds it.
    sector: u16,
    /// Eye-space depth `z'` of its centre: the depth of the whole rectangle.
    depth: f64,
    /// Eye-space `x' − width/2`: the rectangle's left edge.
    left: f64,
    /// Height of the rectangle's top edge, `b + height`.
    top: f64,
    sprite: &'a Sprite<'a>,
    /// Drawn over what is behind it through the blend table.
    translucent: bool,
    /// The columns whose ray may meet the rectangle (a superset: `u` decides).
    first_column: usize,
    end_column: usize,
}

/// A thing that a column's ray meets at sprite column `u`, and the first position of its sector
/// on the column's path.
#[derive(Clone, Copy, Debug)]
struct Candidate<'a> {
    thing: ThingView<'a>,
    position: usize,
    u: usize,
}

/// The middle image of a portal a column's ray crosses: the exit wall of the segment at
/// `position` of the path, with everything but the row worked out.
#[derive(Clone, Copy, Debug)]
struct MiddleView<'a> {
    position: usize,
    wall: u16,
    /// The wall's own sector (the near side), whose light it takes.
    sector: u16,
    /// The crossing's depth, the segment's `t_out`.
    depth: f64,
    /// The image's top edge: the lower of the two ceilings plus the wall's y offset.
    top: f64,
    /// The image column, `floor(u) mod width`.
    u: usize,
    sprite: &'a Sprite<'a>,
    translucent: bool,
}

/// Something a pixel's ray meets in front of the surface that stops it: a thing or a middle,
/// at an opaque texel, lit.
#[derive(Clone, Copy, Debug)]
struct Front {
    depth: f64,
    /// Order of equal depths, nearest first: a thing in the sector at path position `p` is
    /// `2p`, the middle crossed out of it `2p + 1` (a thing on the near side covers the middle,
    /// one on the far side is covered), then the later thing in the map's table first.
    rank: (usize, u16),
    surface: Surface,
    index: u8,
    translucent: bool,
}

/// Where a pixel centre lies exactly on an edge (an axis-aligned view of integer geometry puts
/// many there), the engine's half-open rules give the pixel to the surface below the edge
/// (rows: a span `[y0, y1)` owns rows `ceil(y0 − ½)..`) and right of it (columns: a ray through
/// a vertex belongs to the wall that starts there). The oracle casts through a point this far
/// (in pixels) right of and below each centre, so exact ties break the same way, while any
/// pixel whose centre is not on an edge is unaffected.
pub const TIE_NUDGE: f64 = 1.0 / 1048576.0;

/// [`TIE_NUDGE`] for columns: 2^-42 of a pixel. The engine decides which wall owns a column
/// exactly on the column's ray ([`portalcast::math::ExactEyePoint`]), so a vertex that is not
/// exactly on a ray is at least 2^-32 units off it (its eye coordinates are whole 2^-24 units,
/// the ray's slope a ratio of columns to at most 240): the nudge must move the ray less than
/// that at the farthest depth (2^14.5 units) and still more than f64's rounding, so that the
/// oracle's columns break exact ties and only exact ties the engine's way.
pub const COLUMN_TIE_NUDGE: f64 = 1.0 / 4_398_046_511_104.0;

/// The view direction `(sin, cos)` the engine uses for `camera`: its 16.16 sine and cosine of
/// the binary angle nearest the camera's angle, as a unit vector. The engine's columns are rays
/// of that direction; the oracle casts the same ones (issue 16: the exact sine and cosine turned
/// the view by up to 1e-5 radians against the engine's, and gave columns whose rays pass within
/// a thousandth of a pixel of a vertex to other walls).
pub fn engine_direction(camera: &Camera) -> (f64, f64) {
    let (sin, cos) = portalcast::math::Angle::from_bits(camera.angle_bits()).sin_cos();
    let (sin, cos) = (f64::from(sin.to_bits()), f64::from(cos.to_bits()));
    let length = sin.hypot(cos);
    (sin / length, cos / length)
}

/// Renders `map` from `camera` with one exact ray per pixel.
///
/// The march and the surfaces are those of the crate documentation; the texels follow
/// `portalcast::render::surface`:
/// - walls and strips: `u = s·length + x_offset` (along the wall from its start vertex),
///   `v = anchor − h(t_out) + y_offset` with the anchor at the near sector's ceiling for walls
///   and upper strips and at the neighbour's floor for lower strips; mip level from `t_out`;
/// - floors and ceilings: the map point `P + t·D` at the plane hit, mip level from that `t`;
/// - the sky: column `floor(angle(D) / 2π · sky_width) mod sky_width`, row
///   `floor((y + ½ − horizon_y) · 160 / height) + sky_height / 2` clamped to the image;
/// - a texture slot of [`NO_TEXTURE`] (or [`SKY`] anywhere but a ceiling) where a surface is
///   drawn gives texel 0, as the engine's blank column does;
/// - things: the crate documentation's "Things" (the pixel's ray meets each thing of a sector it
///   reaches at `u`, `v` of the rule; the nearest at an opaque texel shows);
/// - middles and translucency: the crate documentation's "Middles and translucency".
///
/// Light: the final index is `colormap[row][texel]` with
/// `row = light_row(light, floor(depth), lighting)` when that is `Some`, else the texel; the
/// light is the near sector's for walls, strips and middles, the plane's sector for flats, the
/// thing's sector for things, with `depth` the hit's `t` (a thing's `z'`, a middle's crossing
/// `t_out`). The sky is never lit.
///
/// If `camera.sector` is `None` and no sector strictly contains the eye, every pixel is
/// [`Surface::None`] (index 0, depth infinite): a camera on a wall line is an input error the
/// comparison should see, not a panic.
///
/// Panics if a texture slot other than [`NO_TEXTURE`] is out of range of `assets.textures`
/// or lacks the chain (columns or rows) it is drawn with, or if a thing's or a middle's sprite
/// set is out of range of `assets.sprite_sets` or its image of `assets.sprites`.
///
/// Rays go through the pixel centres moved by [`TIE_NUDGE`].
pub fn render(map: &MapTables, assets: &Assets, camera: &Camera, view: &View) -> Frame {
    let (width, height) = (view.width, view.height);
    let mut frame = Frame {
        width,
        height,
        surfaces: vec![Surface::None; width * height],
        indices: vec![0; width * height],
        depths: vec![f64::INFINITY; width * height],
        wall_sectors: wall_sectors(map),
        thing_sectors: thing_sectors(map),
        plane_groups: plane_groups(map),
    };
    let Some(start) = camera.sector.or_else(|| {
        find_sector(map, camera.x, camera.y)
            .map(|found| map.sector_at_height(found, (camera.eye_z * 256.0).floor() as i32))
    }) else {
        return frame;
    };
    let eye = Vec2::new(camera.x, camera.y);
    let (sin, cos) = engine_direction(camera);
    let max_steps = map.sectors.len() + 8;
    let mut path = Vec::with_capacity(max_steps);
    let things = thing_views(map, assets, camera, view, &frame.thing_sectors);
    let mut candidates = Vec::new();
    let mut middles = Vec::new();
    let mut fronts = Vec::new();
    // A row whose ray passes a floor or ceiling portal: its path from there, and what stands
    // in front along it.
    let (mut layered, mut layered_candidates, mut layered_middles) =
        (Vec::new(), Vec::new(), Vec::new());
    for column in 0..width {
        let m = (column as f64 - width as f64 / 2.0 + 0.5 + COLUMN_TIE_NUDGE) / view.focal_x;
        let d = Vec2::new(cos - m * sin, sin + m * cos);
        trace_column(map, start, eye, d, max_steps, &mut path);
        column_candidates(&things, &path, column, m, &mut candidates);
        column_middles(map, assets, &path, &mut middles);
        let sky_column = sky_column(assets, d);
        for row in 0..height {
            let k = (row as f64 + 0.5 + TIE_NUDGE - view.horizon_y) / view.focal_y;
            let (mut hit, mut reached) = shade_ray(map, &path, (eye, d), camera.eye_z, k);
            let mut on_layers = false;
            while let Some(beyond) = layer_beyond(map, &hit) {
                // Through the plane into the sector beyond, whose outline is the same: the
                // path so far, then onwards from there.
                let kept = reached - 1;
                if on_layers {
                    layered.truncate(kept);
                } else {
                    layered.clear();
                    layered.extend_from_slice(&path[..kept]);
                    on_layers = true;
                }
                let t_in = layered.last().map_or(0.0, |segment| segment.t_out);
                trace_onwards(map, (beyond, t_in), eye, d, max_steps, &mut layered);
                (hit, reached) = shade_ray(map, &layered, (eye, d), camera.eye_z, k);
            }
            let (candidates, middles) = if on_layers {
                column_candidates(&things, &layered, column, m, &mut layered_candidates);
                column_middles(map, assets, &layered, &mut layered_middles);
                (&layered_candidates, &layered_middles)
            } else {
                (&candidates, &middles)
            };
            pixel_fronts(
                map,
                assets,
                view,
                candidates,
                middles,
                reached,
                camera.eye_z,
                k,
                &mut fronts,
            );
            let shade_hit = || match hit {
                Hit::None => (Surface::None, 0, f64::INFINITY),
                Hit::Sky => (
                    Surface::Sky,
                    sky_texel(assets, view, sky_column, row),
                    f64::INFINITY,
                ),
                Hit::Flat {
                    surface,
                    sector,
                    texture,
                    t,
                } => {
                    let x = eye.x + t * d.x;
                    let y = eye.y + t * d.y;
                    let texel = flat_texel(assets, texture, t, view.focal_y, x, y);
                    (surface, lit(map, assets, view, sector, t, texel), t)
                }
                Hit::Wall {
                    surface,
                    sector,
                    texture,
                    t,
                    u,
                    v,
                } => {
                    let texel = wall_texel(assets, texture, t, view.focal_y, u, v);
                    (surface, lit(map, assets, view, sector, t, texel), t)
                }
            };
            let (surface, index, depth) = match fronts.first() {
                None => shade_hit(),
                Some(nearest) => {
                    // The nearest front that hides what is behind it (an opaque one, or any
                    // when there is no blend table), or the hit; then each translucent front
                    // before it, back to front, over that.
                    let covering = fronts
                        .iter()
                        .position(|front| !front.translucent || assets.blend.is_none());
                    let (mut index, over) = match covering {
                        Some(at) => (fronts[at].index, &fronts[..at]),
                        None => (shade_hit().1, &fronts[..]),
                    };
                    if let Some(blend) = assets.blend {
                        for front in over.iter().rev() {
                            index = blend[usize::from(index)][usize::from(front.index)];
                        }
                    }
                    (nearest.surface, index, nearest.depth)
                }
            };
            let pixel = row * width + column;
            frame.surfaces[pixel] = surface;
            frame.indices[pixel] = index;
            frame.depths[pixel] = depth;
        }
    }
    frame
}

/// Every sector's plane group ([`Frame::plane_groups`]): the least sector index reachable
/// through portals without a middle image between neighbours with the same planes.
pub fn plane_groups(map: &MapTables) -> Vec<u16> {
    let mut groups: Vec<u16> = (0..map.sectors.len() as u16).collect();
    fn root(groups: &[u16], mut sector: u16) -> u16 {
        while groups[usize::from(sector)] != sector {
            sector = groups[usize::from(sector)];
        }
        sector
    }
    for (index, sector) in map.sectors.iter().enumerate() {
        for wall in map.sector_walls(sector) {
            let Some(neighbour) = map.sectors.get(usize::from(wall.portal)) else {
                continue;
            };
            if wall.middle == NO_TEXTURE && same_planes(sector, neighbour) {
                let (a, b) = (root(&groups, index as u16), root(&groups, wall.portal));
                groups[usize::from(a.max(b))] = a.min(b);
            }
        }
    }
    (0..map.sectors.len() as u16)
        .map(|sector| root(&groups, sector))
        .collect()
}

/// The owner sector of every wall (`u16::MAX` for a wall no sector lists).
fn wall_sectors(map: &MapTables) -> Vec<u16> {
    let mut owners = vec![u16::MAX; map.walls.len()];
    for (index, sector) in map.sectors.iter().enumerate() {
        let first = usize::from(sector.first_wall);
        for owner in &mut owners[first..first + usize::from(sector.wall_count)] {
            *owner = index as u16;
        }
    }
    owners
}

/// The sector of every thing of the map: the one whose group of
/// [`MapTables::sector_things`] holds it (`u16::MAX` for a thing in none).
fn thing_sectors(map: &MapTables) -> Vec<u16> {
    let mut sectors = vec![u16::MAX; map.things.len()];
    for (sector, range) in map
        .sector_things
        .windows(2)
        .take(map.sectors.len())
        .enumerate()
    {
        let (first, end) = (usize::from(range[0]), usize::from(range[1]));
        for owner in &mut sectors[first..end] {
            *owner = sector as u16;
        }
    }
    sectors
}

/// The image of `thing`'s sprite set at the view's tick, seen from the eye at `(-dx, -dy)` from
/// it: the animation frame `floor(tick / frame_ticks) mod frames`, and of eight rotations the
/// one nearest the angle from the thing's facing to the direction of the eye, measured in the
/// direction of growing binary angles (f64 `atan2`, the rule of `SpriteSet`).
fn image_of<'a>(
    assets: &Assets<'a>,
    view: &View,
    thing: &portalcast_format::Thing,
    dx: f64,
    dy: f64,
) -> Option<&'a portalcast_format::Sprite<'a>> {
    let set = assets.sprite_sets.get(usize::from(thing.sprite))?;
    let frame = (view.tick / u32::from(thing.frame_ticks.max(1))) % u32::from(set.frames);
    let rotation = if set.rotations == 8 {
        let to_eye = (-dy).atan2(-dx);
        let facing = crate::angle_from_bits(thing.angle);
        let turns = (to_eye - facing).rem_euclid(core::f64::consts::TAU) / core::f64::consts::TAU;
        ((turns * 8.0).round() as u32) % 8
    } else {
        0
    };
    let image =
        usize::from(set.first) + frame as usize * usize::from(set.rotations) + rotation as usize;
    assets.sprites.get(image)
}

/// The things of the map in eye space, those at least [`THING_DEPTH_MIN`] deep, nearest first
/// (ties: the later in the map's table first), so the first one a pixel's ray meets is the one
/// it shows.
fn thing_views<'a>(
    map: &MapTables,
    assets: &Assets<'a>,
    camera: &Camera,
    view: &View,
    thing_sectors: &[u16],
) -> Vec<ThingView<'a>> {
    let (sin, cos) = engine_direction(camera);
    let mut views: Vec<ThingView<'a>> = map
        .things
        .iter()
        .zip(thing_sectors)
        .enumerate()
        .filter(|(_, (_, &sector))| sector != u16::MAX)
        .filter_map(|(index, (thing, &sector))| {
            let dx = f64::from(thing.x_fx8) / 256.0 - camera.x;
            let dy = f64::from(thing.y_fx8) / 256.0 - camera.y;
            let x = dx * -sin + dy * cos;
            let depth = dx * cos + dy * sin;
            if depth < f64::from(THING_DEPTH_MIN) {
                return None;
            }
            let sprite = image_of(assets, view, thing, dx, dy).unwrap_or_else(|| {
                panic!(
                    "thing {index}: sprite set {} out of range ({} sets, {} images)",
                    thing.sprite,
                    assets.sprite_sets.len(),
                    assets.sprites.len()
                )
            });
            let (width, height) = (f64::from(sprite.width), f64::from(sprite.height));
            let sector_heights = &map.sectors[usize::from(sector)];
            let top = if thing.flags & THING_HANGING != 0 {
                f64::from(sector_heights.ceil_z) - f64::from(thing.z)
            } else {
                f64::from(sector_heights.floor_z) + f64::from(thing.z) + height
            };
            let left = x - width / 2.0;
            // Column c's ray is at `m·z'` across with `m = (c + ½ + nudge − W/2) / focal_x`: the
            // rectangle's `[left, left + width)` is the columns around these, one more each side
            // for the rounding.
            let column_at =
                |across: f64| across / depth * view.focal_x + view.width as f64 / 2.0 - 0.5;
            let first = (column_at(left).floor() - 1.0).max(0.0);
            let end = (column_at(left + width).ceil() + 2.0).clamp(0.0, view.width as f64);
            Some(ThingView {
                index: index as u16,
                sector,
                depth,
                left,
                top,
                sprite,
                translucent: thing.flags & THING_TRANSLUCENT != 0,
                first_column: first as usize,
                end_column: end as usize,
            })
        })
        .collect();
    views.sort_by(|a, b| a.depth.total_cmp(&b.depth).then(b.index.cmp(&a.index)));
    views
}

/// The things column `column` (slope `m`) may show: those whose rectangle its ray crosses
/// (`0 ≤ u < width`) in a sector of its `path`, in the order of `things`.
fn column_candidates<'a>(
    things: &[ThingView<'a>],
    path: &[Segment],
    column: usize,
    m: f64,
    candidates: &mut Vec<Candidate<'a>>,
) {
    candidates.clear();
    for thing in things {
        if column < thing.first_column || column >= thing.end_column {
            continue;
        }
        let u = (m * thing.depth - thing.left).floor();
        if u < 0.0 || u >= f64::from(thing.sprite.width) {
            continue;
        }
        let Some(position) = path.iter().position(|s| s.sector == thing.sector) else {
            continue;
        };
        candidates.push(Candidate {
            thing: *thing,
            position,
            u: u as usize,
        });
    }
}

/// The middle images of the portals the column's `path` crosses (the exit walls of its
/// segments that have one), in the path's order.
fn column_middles<'a>(
    map: &MapTables,
    assets: &Assets<'a>,
    path: &[Segment],
    middles: &mut Vec<MiddleView<'a>>,
) {
    middles.clear();
    for (position, segment) in path.iter().enumerate() {
        let wall = &map.walls[usize::from(segment.wall)];
        if wall.middle == NO_TEXTURE {
            continue;
        }
        let Some(next) = wall.neighbour() else {
            continue;
        };
        let sprite = middle_image(assets, wall.middle).unwrap_or_else(|| {
            panic!(
                "wall {}: middle sprite set {} out of range ({} sets, {} images)",
                segment.wall,
                wall.middle,
                assets.sprite_sets.len(),
                assets.sprites.len()
            )
        });
        let sector = &map.sectors[usize::from(segment.sector)];
        let neighbour = &map.sectors[usize::from(next)];
        // The wall's `u`, as `segment_hit` computes it for the strips.
        let u = segment.s * wall_length(map, wall) + f64::from(wall.x_offset);
        middles.push(MiddleView {
            position,
            wall: segment.wall,
            sector: segment.sector,
            depth: segment.t_out,
            top: f64::from(sector.ceil_z.min(neighbour.ceil_z)) + f64::from(wall.y_offset),
            u: (u.floor() as i64).rem_euclid(i64::from(sprite.width)) as usize,
            sprite,
            translucent: wall.flags & WALL_MIDDLE_TRANSLUCENT != 0,
        });
    }
}

/// The image of the middle sprite set `set`: its first (a middle is a still image).
fn middle_image<'a>(assets: &Assets<'a>, set: u16) -> Option<&'a Sprite<'a>> {
    let set = assets.sprite_sets.get(usize::from(set))?;
    assets.sprites.get(usize::from(set.first))
}

/// What the ray of slope `k` meets in front of the surface that stops it, nearest first: the
/// things of `candidates` in a sector among the first `reached` of the path, and the middles
/// of the portals it passes (out of the first `reached − 1` segments), where it meets them at
/// an opaque texel.
#[allow(clippy::too_many_arguments)]
fn pixel_fronts(
    map: &MapTables,
    assets: &Assets,
    view: &View,
    candidates: &[Candidate],
    middles: &[MiddleView],
    reached: usize,
    eye_z: f64,
    k: f64,
    fronts: &mut Vec<Front>,
) {
    fronts.clear();
    for candidate in candidates {
        if candidate.position >= reached {
            continue;
        }
        let thing = &candidate.thing;
        let Some(texel) =
            upright_texel(thing.sprite, candidate.u, thing.top, thing.depth, eye_z, k)
        else {
            continue;
        };
        fronts.push(Front {
            depth: thing.depth,
            rank: (2 * candidate.position, u16::MAX - thing.index),
            surface: Surface::Thing(thing.index),
            index: lit(map, assets, view, thing.sector, thing.depth, texel),
            translucent: thing.translucent,
        });
    }
    for middle in middles {
        // The ray passes the portal only if the segment's sector did not stop it.
        if middle.position + 1 >= reached {
            break;
        }
        let Some(texel) =
            upright_texel(middle.sprite, middle.u, middle.top, middle.depth, eye_z, k)
        else {
            continue;
        };
        fronts.push(Front {
            depth: middle.depth,
            rank: (2 * middle.position + 1, 0),
            surface: Surface::Middle(middle.wall),
            index: lit(map, assets, view, middle.sector, middle.depth, texel),
            translucent: middle.translucent,
        });
    }
    if fronts.len() > 1 {
        fronts.sort_by(|a, b| a.depth.total_cmp(&b.depth).then(a.rank.cmp(&b.rank)));
    }
}

/// The sectors the 2D ray `eye + t·d` crosses from `start`, up to its solid wall or
/// `max_steps` sectors.
fn trace_column(
    map: &MapTables,
    start: u16,
    eye: Vec2,
    d: Vec2,
    max_steps: usize,
    path: &mut Vec<Segment>,
) {
    path.clear();
    trace_onwards(map, (start, 0.0), eye, d, max_steps, path);
}

/// The sector a floor or ceiling portal leads into, where `hit` is one (room over room).
fn layer_beyond(map: &MapTables, hit: &Hit) -> Option<u16> {
    match *hit {
        Hit::Flat {
            surface: Surface::Ceiling(sector),
            ..
        } => map.sector_above(sector),
        Hit::Flat {
            surface: Surface::Floor(sector),
            ..
        } => map.sector_below(sector),
        _ => None,
    }
}

/// Appends to `path` the sectors the 2D ray `eye + t·d` crosses from sector `start`, which it
/// is in from depth `t_in`, up to its solid wall or `max_steps` sectors in all.
fn trace_onwards(
    map: &MapTables,
    (start, t_in): (u16, f64),
    eye: Vec2,
    d: Vec2,
    max_steps: usize,
    path: &mut Vec<Segment>,
) {
    let (mut sector, mut t_in) = (start, t_in);
    while path.len() < max_steps {
        let Some(exit) = exit_wall(map, &map.sectors[usize::from(sector)], eye, d) else {
            return;
        };
        let t_out = exit.t.max(t_in);
        path.push(Segment {
            sector,
            t_out,
            wall: exit.wall,
            s: exit.s,
        });
        match map.walls[usize::from(exit.wall)].neighbour() {
            None => return,
            Some(next) => {
                sector = next;
                t_in = t_out;
            }
        }
    }
}

/// What the ray of slope `k` (down per unit of depth) hits along the column's `path`, and how
/// many of the path's segments it reaches: up to and including the one whose surface stopped it,
/// all of them if none did.
fn shade_ray(
    map: &MapTables,
    path: &[Segment],
    ray: (Vec2, Vec2),
    eye_z: f64,
    k: f64,
) -> (Hit, usize) {
    path.iter()
        .enumerate()
        .find_map(|(position, segment)| {
            let sector = &map.sectors[usize::from(segment.sector)];
            let neighbour = map.walls[usize::from(segment.wall)]
                .neighbour()
                .map(|next| &map.sectors[usize::from(next)]);
            let hit = if sector.slope == NO_SLOPE && neighbour.is_none_or(|n| n.slope == NO_SLOPE) {
                segment_hit(map, segment, eye_z, k)
            } else {
                sloped_segment_hit(map, segment, ray, eye_z, k)
            };
            hit.map(|hit| (hit, position + 1))
        })
        .unwrap_or((Hit::None, path.len()))
}

/// A plane's height at `p`, in f64 from its stored fixed point (the plane the engine draws).
fn plane_height(plane: &Plane, p: Vec2) -> f64 {
    f64::from(plane.base_fx8) / 256.0
        + (f64::from(plane.gradient_x_fx24) * p.x + f64::from(plane.gradient_y_fx24) * p.y)
            / f64::from(1 << 24)
}

/// [`segment_hit`] where the segment's sector or the one beyond its exit slopes: the ray
/// `eye + t·d` at height `eye_z − k·t` passes a plane `z = z_e + t·g` (its height above the 2D
/// ray, `z_e` under the eye, `g` its rise along `d`) where `eye_z − z_e = t·(k + g)`. Either
/// plane may be met whatever the sign of `k`; the heights at the exit point decide, with the
/// same ties as [`segment_hit`].
fn sloped_segment_hit(
    map: &MapTables,
    segment: &Segment,
    (eye, d): (Vec2, Vec2),
    eye_z: f64,
    k: f64,
) -> Option<Hit> {
    let sector = &map.sectors[usize::from(segment.sector)];
    let planes = map.planes(sector);
    let exit = Vec2::new(eye.x + segment.t_out * d.x, eye.y + segment.t_out * d.y);
    let h_out = eye_z - k * segment.t_out;
    let crossing = |plane: &Plane| {
        let under_eye = plane_height(plane, eye);
        let rise = (f64::from(plane.gradient_x_fx24) * d.x
            + f64::from(plane.gradient_y_fx24) * d.y)
            / f64::from(1 << 24);
        (eye_z - under_eye) / (k + rise)
    };
    if h_out > plane_height(&planes.ceiling, exit) {
        if sector.ceil_texture == SKY {
            return Some(Hit::Sky);
        }
        return Some(Hit::Flat {
            surface: Surface::Ceiling(segment.sector),
            sector: segment.sector,
            texture: sector.ceil_texture,
            t: crossing(&planes.ceiling),
        });
    }
    if h_out <= plane_height(&planes.floor, exit) {
        return Some(Hit::Flat {
            surface: Surface::Floor(segment.sector),
            sector: segment.sector,
            texture: sector.floor_texture,
            t: crossing(&planes.floor),
        });
    }
    let wall = &map.walls[usize::from(segment.wall)];
    let u = segment.s * wall_length(map, wall) + f64::from(wall.x_offset);
    let at = |surface, texture, anchor: i32| Hit::Wall {
        surface,
        sector: segment.sector,
        texture,
        t: segment.t_out,
        u,
        v: f64::from(anchor) - h_out + f64::from(wall.y_offset),
    };
    let Some(next) = wall.neighbour() else {
        return Some(at(
            Surface::Wall(segment.wall),
            map.solid_texture(segment.wall, wall),
            sector.ceil_z,
        ));
    };
    let neighbour = &map.sectors[usize::from(next)];
    let beyond = map.planes(neighbour);
    let (ceiling, neighbour_ceiling) = (
        plane_height(&planes.ceiling, exit),
        plane_height(&beyond.ceiling, exit),
    );
    if neighbour_ceiling < ceiling && h_out > neighbour_ceiling {
        if sector.ceil_texture == SKY && neighbour.ceil_texture == SKY {
            return Some(Hit::Sky);
        }
        return Some(at(
            Surface::Upper(segment.wall),
            wall.upper_texture,
            sector.ceil_z,
        ));
    }
    let (floor, neighbour_floor) = (
        plane_height(&planes.floor, exit),
        plane_height(&beyond.floor, exit),
    );
    if neighbour_floor > floor && h_out <= neighbour_floor {
        return Some(at(
            Surface::Lower(segment.wall),
            wall.lower_texture,
            neighbour.floor_z,
        ));
    }
    None
}

/// What the ray of slope `k` hits in `segment`'s sector, if it does not go on to the next.
fn segment_hit(map: &MapTables, segment: &Segment, eye_z: f64, k: f64) -> Option<Hit> {
    let sector = &map.sectors[usize::from(segment.sector)];
    let (ceil_z, floor_z) = (f64::from(sector.ceil_z), f64::from(sector.floor_z));
    let h_out = eye_z - k * segment.t_out;
    // h is monotonic in t and was within the sector's heights at t_in, so passing a plane's
    // height by t_out means hitting the plane in [t_in, t_out]. Exact ties go to the surface
    // below on screen, as the engine's row rule `y0 ≤ y + ½ < y1` does: the wall under a
    // ceiling, the floor under a wall.
    if k < 0.0 && h_out > ceil_z {
        if sector.ceil_texture == SKY {
            return Some(Hit::Sky);
        }
        let t = (eye_z - ceil_z) / k;
        let surface = Surface::Ceiling(segment.sector);
        return Some(Hit::Flat {
            surface,
            sector: segment.sector,
            texture: sector.ceil_texture,
            t,
        });
    }
    if k > 0.0 && h_out <= floor_z {
        let t = (eye_z - floor_z) / k;
        let surface = Surface::Floor(segment.sector);
        return Some(Hit::Flat {
            surface,
            sector: segment.sector,
            texture: sector.floor_texture,
            t,
        });
    }
    let wall = &map.walls[usize::from(segment.wall)];
    let u = segment.s * wall_length(map, wall) + f64::from(wall.x_offset);
    let at = |surface, texture, anchor: i32| Hit::Wall {
        surface,
        sector: segment.sector,
        texture,
        t: segment.t_out,
        u,
        v: f64::from(anchor) - h_out + f64::from(wall.y_offset),
    };
    let Some(next) = wall.neighbour() else {
        return Some(at(
            Surface::Wall(segment.wall),
            map.solid_texture(segment.wall, wall),
            sector.ceil_z,
        ));
    };
    let neighbour = &map.sectors[usize::from(next)];
    // Ties again go down the screen: past the upper strip's bottom edge into the opening,
    // onto the lower strip at its top edge.
    if neighbour.ceil_z < sector.ceil_z && h_out > f64::from(neighbour.ceil_z) {
        if sector.ceil_texture == SKY && neighbour.ceil_texture == SKY {
            return Some(Hit::Sky);
        }
        return Some(at(
            Surface::Upper(segment.wall),
            wall.upper_texture,
            sector.ceil_z,
        ));
    }
    if neighbour.floor_z > sector.floor_z && h_out <= f64::from(neighbour.floor_z) {
        return Some(at(
            Surface::Lower(segment.wall),
            wall.lower_texture,
            neighbour.floor_z,
        ));
    }
    None
}

fn wall_length(map: &MapTables, wall: &Wall) -> f64 {
    let a = vertex(map, wall.start);
    let b = vertex(map, wall.end);
    (b.x - a.x).hypot(b.y - a.y)
}

/// The mip level at eye-space depth `depth`: `floor(log2(depth / focal_y))`, at least 0 and
/// below `mip_count` (the rule of `portalcast::render::surface`).
pub fn mip_level(depth: f64, focal_y: f64, mip_count: u8) -> u8 {
    let ratio = depth / focal_y;
    // Halving is exact, so the boundaries are exactly the powers of two.
    let mut level = 0u8;
    let mut scale = 2.0;
    while ratio >= scale && level + 1 < mip_count {
        level += 1;
        scale *= 2.0;
    }
    level
}

/// `(floor(c) mod 2^log2) >> level`: a texel coordinate of mip level `level`.
fn texel_coordinate(c: f64, log2: u8, level: u8) -> usize {
    let wrapped = (c.floor() as i64).rem_euclid(1 << log2);
    (wrapped >> level) as usize
}

fn texture<'a>(assets: &Assets<'a>, slot: u16) -> Option<&'a Texture<'a>> {
    if slot == NO_TEXTURE || slot == SKY {
        return None;
    }
    let texture = assets.textures.get(usize::from(slot));
    Some(texture.unwrap_or_else(|| {
        panic!(
            "texture slot {slot} out of range ({} textures)",
            assets.textures.len()
        )
    }))
}

/// The opaque texel of an upright image (a thing's sprite, a portal's middle), column `u`, whose
/// top edge is at height `top` and which the ray meets at depth `depth`: the ray's height there
/// is `eye_z − k·depth`. `None` above or below the image or on a transparent texel.
fn upright_texel(
    sprite: &Sprite,
    u: usize,
    top: f64,
    depth: f64,
    eye_z: f64,
    k: f64,
) -> Option<u8> {
    let v = (top - (eye_z - k * depth)).floor();
    if v < 0.0 || v >= f64::from(sprite.height) {
        return None;
    }
    Some(sprite.texel(u, v as usize)).filter(|&texel| texel != TRANSPARENT)
}

fn wall_texel(assets: &Assets, slot: u16, depth: f64, focal_y: f64, u: f64, v: f64) -> u8 {
    let Some(texture) = texture(assets, slot) else {
        return 0;
    };
    let level = mip_level(depth, focal_y, texture.mip_count);
    let u = texel_coordinate(u, texture.width_log2, level);
    let v = texel_coordinate(v, texture.height_log2, level);
    texture.wall_level(level)[(u << texture.level_height_log2(level)) + v]
}

fn flat_texel(assets: &Assets, slot: u16, depth: f64, focal_y: f64, x: f64, y: f64) -> u8 {
    let Some(texture) = texture(assets, slot) else {
        return 0;
    };
    let level = mip_level(depth, focal_y, texture.mip_count);
    let u = texel_coordinate(x, texture.width_log2, level);
    let v = texel_coordinate(y, texture.height_log2, level);
    texture.flat_level(level)[(v << texture.level_width_log2(level)) + u]
}

/// The sky column of the ray direction `d`.
fn sky_column(assets: &Assets, d: Vec2) -> usize {
    let width = 1i64 << assets.sky.width_log2;
    let angle = d.y.atan2(d.x).rem_euclid(core::f64::consts::TAU);
    ((angle / core::f64::consts::TAU * width as f64).floor() as i64).rem_euclid(width) as usize
}

fn sky_texel(assets: &Assets, view: &View, column: usize, row: usize) -> u8 {
    let sky_height = i64::from(assets.sky.height);
    let offset = ((row as f64 + 0.5 - view.horizon_y) * 160.0 / view.height as f64).floor() as i64;
    let v = (offset + sky_height / 2).clamp(0, sky_height - 1) as usize;
    assets.sky.texels[column * usize::from(assets.sky.height) + v]
}

/// `texel` through the colormap row of `sector`'s light at `depth`, if lighting is on.
fn lit(map: &MapTables, assets: &Assets, view: &View, sector: u16, depth: f64, texel: u8) -> u8 {
    let sector: &Sector = &map.sectors[usize::from(sector)];
    match light_row(sector.light, depth.floor() as i32, view.lighting) {
        Some(row) => assets.colormap[row][usize::from(texel)],
        None => texel,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mip_level_boundaries_are_powers_of_two() {
        // depth / focal_y = 1.999 → 0; 2 → 1; 4 → 2; 3.99 → 1; clamped below mip_count.
        assert_eq!(mip_level(239.9, 120.0, 4), 0);
        assert_eq!(mip_level(240.0, 120.0, 4), 1);
        assert_eq!(mip_level(479.0, 120.0, 4), 1);
        assert_eq!(mip_level(480.0, 120.0, 4), 2);
        assert_eq!(mip_level(10_000.0, 120.0, 4), 3);
        assert_eq!(mip_level(10_000.0, 120.0, 1), 0);
        assert_eq!(mip_level(0.5, 120.0, 4), 0);
    }

    #[test]
    fn texel_coordinates_wrap_then_shrink() {
        // floor(-0.5) = -1 → 7 in an 8-wide texture; at level 1, 7 >> 1 = 3.
        assert_eq!(texel_coordinate(-0.5, 3, 0), 7);
        assert_eq!(texel_coordinate(-0.5, 3, 1), 3);
        assert_eq!(texel_coordinate(35.9, 3, 0), 3);
        // Past the texture's own size the level is 1 texel wide.
        assert_eq!(texel_coordinate(35.9, 3, 4), 0);
    }
}
