//! Per-pixel ray casting and the texture rules of `portalcast::render::surface`, in f64.

use portalcast::render::light::light_row;
use portalcast::render::surface::Surface;
use portalcast_format::{MapTables, Sector, Texture, Wall, NO_TEXTURE, SKY};

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
///   drawn gives texel 0, as the engine's blank column does.
///
/// Light: the final index is `colormap[row][texel]` with
/// `row = light_row(light, floor(depth), lighting)` when that is `Some`, else the texel; the
/// light is the near sector's for walls and strips, the plane's sector for flats, with `depth`
/// the hit's `t`. The sky is never lit.
///
/// If `camera.sector` is `None` and no sector strictly contains the eye, every pixel is
/// [`Surface::None`] (index 0, depth infinite): a camera on a wall line is an input error the
/// comparison should see, not a panic.
///
/// Panics if a texture slot other than [`NO_TEXTURE`] is out of range of `assets.textures`
/// or lacks the chain (columns or rows) it is drawn with.
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
    };
    let Some(start) = camera
        .sector
        .or_else(|| find_sector(map, camera.x, camera.y))
    else {
        return frame;
    };
    let eye = Vec2::new(camera.x, camera.y);
    let (sin, cos) = engine_direction(camera);
    let max_steps = map.sectors.len() + 8;
    let mut path = Vec::with_capacity(max_steps);
    for column in 0..width {
        let m = (column as f64 - width as f64 / 2.0 + 0.5 + COLUMN_TIE_NUDGE) / view.focal_x;
        let d = Vec2::new(cos - m * sin, sin + m * cos);
        trace_column(map, start, eye, d, max_steps, &mut path);
        let sky_column = sky_column(assets, d);
        for row in 0..height {
            let k = (row as f64 + 0.5 + TIE_NUDGE - view.horizon_y) / view.focal_y;
            let hit = shade_ray(map, &path, camera.eye_z, k);
            let pixel = row * width + column;
            let (surface, index, depth) = match hit {
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
            frame.surfaces[pixel] = surface;
            frame.indices[pixel] = index;
            frame.depths[pixel] = depth;
        }
    }
    frame
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
    let mut sector = start;
    let mut t_in = 0.0;
    while path.len() < max_steps {
        let Some(exit) = exit_wall(map, &map.sectors[usize::from(sector)], eye, d) else {
            return;
        };
        // Rounding may put the exit an ulp before the entry; depth never runs backwards.
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

/// What the ray of slope `k` (down per unit of depth) hits along the column's `path`.
fn shade_ray(map: &MapTables, path: &[Segment], eye_z: f64, k: f64) -> Hit {
    for segment in path {
        let sector = &map.sectors[usize::from(segment.sector)];
        let (ceil_z, floor_z) = (f64::from(sector.ceil_z), f64::from(sector.floor_z));
        let h_out = eye_z - k * segment.t_out;
        // h is monotonic in t and was within the sector's heights at t_in, so passing a plane's
        // height by t_out means hitting the plane in [t_in, t_out]. Exact ties go to the surface
        // below on screen, as the engine's row rule `y0 ≤ y + ½ < y1` does: the wall under a
        // ceiling, the floor under a wall.
        if k < 0.0 && h_out > ceil_z {
            if sector.ceil_texture == SKY {
                return Hit::Sky;
            }
            let t = (eye_z - ceil_z) / k;
            let surface = Surface::Ceiling(segment.sector);
            return Hit::Flat {
                surface,
                sector: segment.sector,
                texture: sector.ceil_texture,
                t,
            };
        }
        if k > 0.0 && h_out <= floor_z {
            let t = (eye_z - floor_z) / k;
            let surface = Surface::Floor(segment.sector);
            return Hit::Flat {
                surface,
                sector: segment.sector,
                texture: sector.floor_texture,
                t,
            };
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
            return at(Surface::Wall(segment.wall), wall.texture, sector.ceil_z);
        };
        let neighbour = &map.sectors[usize::from(next)];
        // Ties again go down the screen: past the upper strip's bottom edge into the opening,
        // onto the lower strip at its top edge.
        if neighbour.ceil_z < sector.ceil_z && h_out > f64::from(neighbour.ceil_z) {
            if sector.ceil_texture == SKY && neighbour.ceil_texture == SKY {
                return Hit::Sky;
            }
            return at(
                Surface::Upper(segment.wall),
                wall.upper_texture,
                sector.ceil_z,
            );
        }
        if neighbour.floor_z > sector.floor_z && h_out <= f64::from(neighbour.floor_z) {
            return at(
                Surface::Lower(segment.wall),
                wall.lower_texture,
                neighbour.floor_z,
            );
        }
    }
    Hit::None
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
