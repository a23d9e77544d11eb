//! The f64 reference renderer ("oracle") of portalcast, host only.
//!
//! The engine renders in fixed point, span by span; the oracle renders the same map and camera
//! by casting one exact ray per pixel in `f64`, applying the texture rules of
//! [`portalcast::render::surface`] and the light rule of [`portalcast::render::light`]. The
//! accuracy tests render both and [`compare()`] them: which surface each pixel shows, which palette
//! index it ends with, how far the engine's edges are from the oracle's, and which sectors and
//! things one of them shows and the other does not.
//!
//! # The ray of a pixel
//!
//! Conventions of `docs/ARCHITECTURE.md`: forward `f = (cos a, sin a)`, right
//! `r = (−sin a, cos a)`, with the engine's sine and cosine of the angle ([`engine_direction`]:
//! its 16.16 values, normalised), so that a column's ray is the engine's. Column `c` is sampled at
//! `c + ½` (moved right by [`COLUMN_TIE_NUDGE`]): slope
//! `m = (c + ½ − width/2) / focal_x`, 2D ray `P + t·D` with `D = f + m·r`, so `t` is the
//! eye-space depth `z'`. Row `y` is sampled at `y + ½`: `k = (y + ½ − horizon_y) / focal_y`, and
//! the 3D ray is at height `h(t) = eye_z − k·t`.
//!
//! # The march
//!
//! In sector `S`, from `t_in` (0 in the eye's sector) to `t_out` where the 2D ray leaves `S`
//! through wall `w` (parameter `s ∈ [0, 1)` along `w`: a ray through a vertex leaves through the
//! wall that *starts* there, as the engine's column rule `x0 ≤ c + ½ < x1` assigns it), with
//! `h = h(t_out)`:
//! - the ceiling of `S` if `k < 0` and `h > ceil_z` (the plane is reached before `t_out`), the
//!   sky if that ceiling is [`SKY`](portalcast_format::SKY); the floor if `k > 0` and
//!   `h ≤ floor_z`;
//! - else, at `t_out`: a solid `w` is [`Surface::Wall`]; through a portal to `N`,
//!   [`Surface::Upper`] if `N.ceil_z < S.ceil_z` and `h > N.ceil_z` (but [`Surface::Sky`] when
//!   both ceilings are sky: that strip is never drawn, the panorama shows through);
//!   [`Surface::Lower`] if `N.floor_z > S.floor_z` and `h ≤ N.floor_z`; otherwise the march
//!   goes on in `N` from `t_in = t_out`;
//! - after `sectors + 8` sectors without a hit (a broken map), [`Surface::None`].
//!
//! Where `S` or `N` slopes, every height above is the plane's at the exit point
//! `P + t_out·D` (from its stored fixed-point coefficients, in f64: the plane the engine
//! draws), and a sloped plane may be met whatever the sign of `k`: the ceiling if
//! `h > ceil(P + t_out·D)`, at the depth `t = (eye_z − z_e)/(k + g)` where the ray meets it
//! (`z_e` the plane's height under the eye, `g` its rise per unit of `t` along `D`); the
//! floor likewise with `h ≤ floor(…)`; then the strips with the two sectors' heights at the
//! exit point.
//!
//! # Things
//!
//! A pixel's ray *reaches* the sectors of its path up to and including the one whose surface
//! stopped it (all of them if none did). Every thing of a reached sector is a camera-facing
//! rectangle at its centre's eye depth `z'` (left out nearer than
//! [`THING_DEPTH_MIN`](portalcast::render::surface::THING_DEPTH_MIN)); the pixel's ray meets it
//! at the texel `(u, v)` of the "Things" rule of [`portalcast::render::surface`], and where that
//! texel is opaque the nearest such thing (ties to the later in the map's table) replaces the
//! pixel's surface with [`Surface::Thing`], lit by its sector's light at depth `z'`.
//!
//! # Middles and translucency
//!
//! Where a pixel's ray passes a portal (the exit wall `w` of a segment whose sector did not stop
//! it, so it goes on into the neighbour `N`) and `w` has a middle image (the first image of its
//! sprite set `w.middle`), the crossing at `t_out`, height `h = h(t_out)`, meets the image at
//! column `floor(s·length + x_offset) mod width` and row
//! `v = floor(min(S.ceil_z, N.ceil_z) + y_offset − h)`; where `0 ≤ v < height` and the texel is
//! opaque it is a candidate [`Surface::Middle`] at depth `t_out`, lit by the near sector `S` at
//! that depth.
//!
//! The pixel shows the nearest (by depth) of its things, its middles and the surface that
//! stopped the ray; at equal depth a thing of the portal's near sector (or one before it on the
//! path) is in front of the middle, one behind it is covered, two things are in path order then
//! the later in the map's table first. The surface and depth are the nearest one's. A
//! translucent front (a thing with [`THING_TRANSLUCENT`](portalcast_format::THING_TRANSLUCENT)
//! or a middle of a wall with
//! [`WALL_MIDDLE_TRANSLUCENT`](portalcast_format::WALL_MIDDLE_TRANSLUCENT)) shows
//! `blend[behind][front]`, `behind` being the index the pixel would have without it (the next
//! front, itself possibly translucent, or the surface hit). Without a blend table
//! ([`Assets::blend`] `None`) translucent fronts are drawn opaque.
//!
//! The strict and non-strict comparisons settle exact ties (a pixel centre exactly on the
//! projection of an edge) the way the engine's row rule does: a vertical span `[y0, y1)` owns
//! the rows with `y0 ≤ y + ½ < y1`, so a tied pixel belongs to the surface *below* the edge on
//! screen (the wall under a ceiling edge, the floor under a wall's foot, the opening under an
//! upper strip, the lower strip under the opening), as a tied column belongs to the wall on the
//! right.
//!
//! The 2D part does not depend on the row, so it runs once per column.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod compare;
mod engine;
mod geometry;
mod poses;
mod render;

pub use compare::{
    compare, compare_with_row_tolerance, mismatch_regions, surface_colour, write_diff_png,
    Comparison, MISSED_THING_MIN_PIXELS, ROW_TOLERANCE_PX,
};
pub use engine::{
    bench_run_accuracy, compare_with_engine, EngineComparison, RecordingCanvas, RunAccuracy,
};
pub use geometry::{find_sector, find_sectors};
pub use portalcast::render::light::Lighting;
pub use portalcast::render::surface::Surface;
pub use poses::{sample_poses, Rng};
pub use render::{engine_direction, mip_level, plane_groups, render, COLUMN_TIE_NUDGE, TIE_NUDGE};

/// The oracle's frame of `camera`, then the two frames with every row's ray moved up and down by
/// [`ROW_TOLERANCE_PX`] (the horizon moved the other way), for [`compare_with_row_tolerance`].
pub fn render_with_row_tolerance(
    map: &portalcast_format::MapTables,
    assets: &Assets,
    camera: &Camera,
    view: &View,
) -> (Frame, [Frame; 2]) {
    let moved = |offset: f64| {
        let mut moved = *view;
        moved.horizon_y += offset;
        render(map, assets, camera, &moved)
    };
    (
        render(map, assets, camera, view),
        [moved(ROW_TOLERANCE_PX), moved(-ROW_TOLERANCE_PX)],
    )
}

use portalcast::math::Viewport;
use portalcast_format::{Colormap, Sky, Sprite, Texture};

/// Where the eye is and where it looks, in `f64` world units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// World x.
    pub x: f64,
    /// World y (drawn downward on a top-down view).
    pub y: f64,
    /// Eye height.
    pub eye_z: f64,
    /// View direction in radians: 0 looks along +x, growing toward +y.
    pub angle: f64,
    /// The sector the eye is in; `None` to find it with [`find_sector`].
    pub sector: Option<u16>,
}

impl Camera {
    /// The camera at an engine pose: position and eye height in 24.8 fixed point, binary angle
    /// (65536 per turn). Every engine pose is exactly representable here.
    pub fn from_fixed(
        x_fx8: i32,
        y_fx8: i32,
        eye_z_fx8: i32,
        angle: u16,
        sector: Option<u16>,
    ) -> Camera {
        Camera {
            x: f64::from(x_fx8) / 256.0,
            y: f64::from(y_fx8) / 256.0,
            eye_z: f64::from(eye_z_fx8) / 256.0,
            angle: angle_from_bits(angle),
            sector,
        }
    }

    /// The view direction as the nearest binary angle (65536 per turn).
    pub fn angle_bits(&self) -> u16 {
        angle_to_bits(self.angle)
    }
}

/// Radians of a binary angle (65536 units per turn).
pub fn angle_from_bits(bits: u16) -> f64 {
    f64::from(bits) * core::f64::consts::TAU / 65536.0
}

/// The binary angle nearest to `radians`, wrapped into one turn; exact inverse of
/// [`angle_from_bits`].
pub fn angle_to_bits(radians: f64) -> u16 {
    (radians / core::f64::consts::TAU * 65536.0)
        .round()
        .rem_euclid(65536.0) as u16
}

/// The screen: size, focal lengths, horizon and lighting rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Horizontal focal length, in columns.
    pub focal_x: f64,
    /// Vertical focal length, in rows.
    pub focal_y: f64,
    /// Screen y of the horizon (the row boundary, not a pixel centre).
    pub horizon_y: f64,
    /// The lighting rule, as the engine's.
    pub lighting: Lighting,
    /// The game tick the frame shows (things' animation frames), as the engine's view's.
    pub tick: u32,
}

impl View {
    /// The view of an engine viewport, so both renderers project identically.
    pub fn from_viewport(viewport: &Viewport, lighting: Lighting) -> View {
        View {
            width: viewport.width as usize,
            height: viewport.height as usize,
            focal_x: f64::from(viewport.focal_x),
            focal_y: f64::from(viewport.focal_y),
            horizon_y: f64::from(viewport.horizon_y),
            lighting,
            tick: 0,
        }
    }
}

/// The images a frame is drawn with.
#[derive(Clone, Copy, Debug)]
pub struct Assets<'a> {
    /// Textures, indexed by the map's texture slots (walls need the column chains, floors and
    /// ceilings the row chains).
    pub textures: &'a [Texture<'a>],
    /// The sky panorama.
    pub sky: &'a Sky<'a>,
    /// The light colormap.
    pub colormap: &'a Colormap,
    /// Sprite images, indexed by the sets.
    pub sprites: &'a [Sprite<'a>],
    /// Sprite sets, indexed by [`Thing::sprite`](portalcast_format::Thing::sprite) and
    /// [`Wall::middle`](portalcast_format::Wall::middle).
    pub sprite_sets: &'a [portalcast_format::SpriteSet<'a>],
    /// The 50 % blend of translucent things and middles (`blend[behind][front]`); `None` draws
    /// them opaque.
    pub blend: Option<&'a portalcast_format::BlendTable>,
}

/// A rendered frame, row-major (`y * width + x`).
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// The surface of each pixel.
    pub surfaces: Vec<Surface>,
    /// The final palette index of each pixel (after the colormap when lighting is on).
    pub indices: Vec<u8>,
    /// Eye-space depth `z'` of each pixel's hit; `f64::INFINITY` for the sky and for
    /// [`Surface::None`].
    pub depths: Vec<f64>,
    /// The sector owning each wall of the map (wall index → sector; `u16::MAX` for a wall no
    /// sector lists), so [`compare()`] can tell which sectors a frame shows without the map.
    pub wall_sectors: Vec<u16>,
    /// The sector of each thing of the map (thing index → the sector whose group of
    /// [`MapTables::sector_things`](portalcast_format::MapTables::sector_things) holds it;
    /// `u16::MAX` for a thing in none), as [`Frame::wall_sectors`] for walls.
    pub thing_sectors: Vec<u16>,
    /// The sector each sector's floor and ceiling count as (sector index → the least index of
    /// its plane group): sectors joined by portals without a middle image between neighbours
    /// with the same planes (`portalcast::render::walk::same_planes`) show one floor and one
    /// ceiling, with no edge between them, and the engine draws them as one plane (Doom's
    /// visplanes), so [`compare()`] counts a pixel of either as the same surface.
    pub plane_groups: Vec<u16>,
}

impl Frame {
    /// The surface at column `x`, row `y`.
    pub fn surface(&self, x: usize, y: usize) -> Surface {
        self.surfaces[y * self.width + x]
    }

    /// The palette index at column `x`, row `y`.
    pub fn index(&self, x: usize, y: usize) -> u8 {
        self.indices[y * self.width + x]
    }

    /// The depth at column `x`, row `y`.
    pub fn depth(&self, x: usize, y: usize) -> f64 {
        self.depths[y * self.width + x]
    }

    /// The surface, palette index and depth at column `x`, row `y`: a pixel as a whole.
    pub fn pixel(&self, x: usize, y: usize) -> (Surface, u8, f64) {
        (self.surface(x, y), self.index(x, y), self.depth(x, y))
    }

    /// `surface`, a floor or a ceiling counted as its plane group's ([`Frame::plane_groups`]);
    /// any other surface as it is.
    pub fn plane_surface(&self, surface: Surface) -> Surface {
        plane_surface(&self.plane_groups, surface)
    }

    /// The sector a surface belongs to, as its plane group ([`Frame::plane_groups`]): of the
    /// floor's or ceiling's sector, of the wall's owner for walls, strips and middles, of the
    /// thing's sector for things; `None` for the sky, [`Surface::None`] and unknown walls and
    /// things. A sector of a group is shown wherever its group's floor is, so the sectors a
    /// frame shows are counted by group.
    pub fn sector_of(&self, surface: Surface) -> Option<u16> {
        let group = |s: u16| self.plane_groups.get(usize::from(s)).copied().unwrap_or(s);
        let sector = match surface {
            Surface::Floor(s) | Surface::Ceiling(s) => Some(s),
            Surface::Wall(w) | Surface::Upper(w) | Surface::Lower(w) | Surface::Middle(w) => {
                let owner = self.wall_sectors.get(usize::from(w)).copied();
                owner.filter(|&s| s != u16::MAX)
            }
            Surface::Thing(t) => {
                let owner = self.thing_sectors.get(usize::from(t)).copied();
                owner.filter(|&s| s != u16::MAX)
            }
            Surface::Sky | Surface::None => None,
        };
        sector.map(group)
    }
}

/// `surface`, a floor or a ceiling counted as its plane group's in `groups` (sector index →
/// group, as [`plane_groups`] makes it; a sector past its end is a group of its own); any other
/// surface as it is.
pub fn plane_surface(groups: &[u16], surface: Surface) -> Surface {
    let group = |s: u16| groups.get(usize::from(s)).copied().unwrap_or(s);
    match surface {
        Surface::Floor(s) => Surface::Floor(group(s)),
        Surface::Ceiling(s) => Surface::Ceiling(group(s)),
        other => other,
    }
}
