//! The camera and the per-frame view derived from it.

use crate::frame::Resolution;
use crate::math::{Angle, EyeFrame, Fx24_8, Viewport, WorldPoint};

use super::light::Lighting;

/// Where the eye is and where it looks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Camera {
    /// Position on the map plane.
    pub position: WorldPoint,
    /// Eye height.
    pub eye_z: Fx24_8,
    /// View direction.
    pub angle: Angle,
    /// The sector the eye is in (the player code tracks it).
    pub sector: u16,
    /// Look up/down as a horizon shift, in screen lines (160-line units) from the centre;
    /// clamped to ±[`MAX_LOOK_LINES`].
    pub look_lines: i32,
}

/// How far the horizon may move from the centre, in screen lines: a quarter screen each way,
/// which keeps the two-screen-tall sky panorama covering every row.
pub const MAX_LOOK_LINES: i32 = 40;

/// Quality knobs that change what is drawn or how exactly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Settings {
    /// Render resolution.
    pub resolution: Resolution,
    /// Lighting rule.
    pub lighting: Lighting,
}

/// Everything per frame that follows from the camera and the settings.
#[derive(Clone, Copy, Debug)]
pub struct View {
    /// Eye position and orientation with its sine and cosine.
    pub eye: EyeFrame,
    /// Eye height.
    pub eye_z: Fx24_8,
    /// Screen size, focal lengths and horizon row.
    pub viewport: Viewport,
    /// The eye's sector.
    pub sector: u16,
    /// Lighting rule.
    pub lighting: Lighting,
}

impl View {
    /// The view of `camera` at `settings`.
    pub fn new(camera: &Camera, settings: &Settings) -> View {
        let resolution = settings.resolution;
        let mut viewport = Viewport::new(resolution.width() as i32, resolution.height() as i32);
        let look = camera.look_lines.clamp(-MAX_LOOK_LINES, MAX_LOOK_LINES);
        viewport.horizon_y += look * resolution.height() as i32 / 160;
        View {
            eye: EyeFrame::new(camera.position, camera.angle),
            eye_z: camera.eye_z,
            viewport,
            sector: camera.sector,
            lighting: settings.lighting,
        }
    }
}
