//! The shipped sprite sets with several images: an animated brazier flame (a strip of frames)
//! and a statue seen from eight directions (docs/MAP_FORMAT.md, "Sprites"). Deterministic, as
//! the rest of the painting.

use image::{Rgb, Rgba, RgbaImage};

use crate::paint::{mix, shade};

/// Frames of the brazier's flame.
pub const FLAME_FRAMES: u32 = 4;
/// One flame frame's width and height.
const FLAME_WIDTH: u32 = 16;
const FLAME_HEIGHT: u32 = 24;

/// One frame of the flame.
struct FlameShape {
    /// The row of its tip.
    top: f32,
    /// How far its tip sways, in texels (+ right).
    sway: f32,
    /// Its brightness.
    glow: f32,
    /// The phase of its licking tongues.
    phase: f32,
    /// A spark above it, if any.
    spark: Option<(u32, u32)>,
}

const FLAME_SHAPES: [FlameShape; FLAME_FRAMES as usize] = [
    FlameShape {
        top: 2.0,
        sway: 0.0,
        glow: 1.0,
        phase: 0.0,
        spark: None,
    },
    FlameShape {
        top: 5.0,
        sway: 1.8,
        glow: 0.88,
        phase: 2.1,
        spark: Some((11, 2)),
    },
    FlameShape {
        top: 1.0,
        sway: -1.3,
        glow: 1.06,
        phase: 4.2,
        spark: Some((4, 0)),
    },
    FlameShape {
        top: 4.0,
        sway: -2.4,
        glow: 0.94,
        phase: 1.0,
        spark: None,
    },
];

fn opaque(Rgb([r, g, b]): Rgb<u8>) -> Rgba<u8> {
    Rgba([r, g, b, 255])
}

/// A brazier with a flickering flame, 16×24 a frame: an iron bowl on two splayed legs (the same
/// in every frame) holding a flame whose height, sway, tongues and brightness change from frame
/// to frame, with a spark flying above it in two frames. Returned as a strip, the
/// [`FLAME_FRAMES`] frames side by side (`flame.strip4.png`).
pub fn flame_strip() -> RgbaImage {
    let clear = Rgba([0, 0, 0, 0]);
    RgbaImage::from_fn(FLAME_WIDTH * FLAME_FRAMES, FLAME_HEIGHT, |x, y| {
        let frame = (x / FLAME_WIDTH) as usize;
        let x = x % FLAME_WIDTH;
        let FlameShape {
            top,
            sway,
            glow,
            phase,
            spark,
        } = FLAME_SHAPES[frame];
        let (xf, yf) = (x as f32 + 0.5, y as f32 + 0.5);
        let dx = xf - 8.0;
        if spark == Some((x, y)) {
            return Rgba([255, 210, 90, 255]);
        }
        // Bowl: rows 16..20, 14 wide at its rim narrowing to 8, lit from the left.
        if (16.0..20.0).contains(&yf) {
            let half = 7.0 - (yf - 16.0);
            if dx.abs() > half {
                return clear;
            }
            let light = if y == 16 { 1.5 } else { 1.1 - 0.05 * dx };
            return opaque(shade([72.0, 64.0, 58.0], light));
        }
        // Legs: rows 20..24, splaying out from under the bowl.
        if yf >= 20.0 {
            let spread = 2.5 + (yf - 20.0) * 0.75;
            return if (dx.abs() - spread).abs() <= 0.75 {
                opaque(shade([60.0, 54.0, 50.0], if dx < 0.0 { 1.2 } else { 0.85 }))
            } else {
                clear
            };
        }
        // Flame: from its tip down into the bowl, widest at the bottom, its edge licking.
        if yf < top {
            return clear;
        }
        let t = (yf - top) / (16.0 - top);
        let centre = 8.0 + sway * (1.0 - t) * (1.0 - t);
        let tongues = 0.9 * (yf * 1.3 + phase).sin() * (1.0 - t);
        let half = (6.0 * t.powf(0.7) + tongues).max(0.0);
        let off = (xf - centre).abs();
        if off > half {
            return clear;
        }
        let core = 1.0 - off / half.max(0.01);
        let colour = mix(
            [215.0, 45.0, 15.0],
            [255.0, 240.0, 150.0],
            core * 0.9 + t * 0.25 - 0.1,
        );
        opaque(shade(colour, glow))
    })
}

/// Width and height of a statue view.
const STATUE_WIDTH: u32 = 24;
const STATUE_HEIGHT: u32 = 48;

/// A solid of the statue, in its own frame: `f` forward (the way it faces), `s` to its right
/// (facing + 90°), `z` up from the bottom of the plinth.
#[derive(Clone, Copy)]
enum Solid {
    /// A vertical column (a cone when the radii differ): axis at (f, s), radius `r0` at `z0`
    /// to `r1` at `z1`.
    Column {
        f: f32,
        s: f32,
        r0: f32,
        r1: f32,
        z0: f32,
        z1: f32,
    },
    /// A ball.
    Ball { f: f32, s: f32, z: f32, r: f32 },
    /// A round plate facing its left (−s): centre (f, z), radius `r`, from `s0` to `s1`.
    Plate {
        f: f32,
        z: f32,
        r: f32,
        s0: f32,
        s1: f32,
    },
}

impl Solid {
    /// The outward normal at `p` if `p` is inside.
    fn normal_inside(self, [pf, ps, pz]: [f32; 3]) -> Option<[f32; 3]> {
        match self {
            Solid::Column {
                f,
                s,
                r0,
                r1,
                z0,
                z1,
            } => {
                if !(z0..z1).contains(&pz) {
                    return None;
                }
                let r = r0 + (r1 - r0) * (pz - z0) / (z1 - z0);
                let (df, ds) = (pf - f, ps - s);
                let d = (df * df + ds * ds).sqrt();
                (d <= r).then(|| [df / d.max(1e-3), ds / d.max(1e-3), 0.0])
            }
            Solid::Ball { f, s, z, r } => {
                let d = [pf - f, ps - s, pz - z];
                let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                (length <= r).then(|| d.map(|c| c / length.max(1e-3)))
            }
            Solid::Plate { f, z, r, s0, s1 } => {
                let inside = (s0..=s1).contains(&ps) && (pf - f).hypot(pz - z) <= r;
                inside.then_some([0.0, -1.0, 0.0])
            }
        }
    }
}

/// A part of the statue: its solid and its paint at a point of it.
struct Part {
    solid: Solid,
    paint: fn([f32; 3]) -> [f32; 3],
}

const SKIN: [f32; 3] = [240.0, 205.0, 170.0];
const HAIR: [f32; 3] = [70.0, 45.0, 25.0];
const ROBE: [f32; 3] = [60.0, 75.0, 165.0];
const GOLD: [f32; 3] = [230.0, 185.0, 60.0];

/// The statue's parts, the first that holds a point painting it: a guard in a blue robe and a
/// steel breastplate on a stone plinth, a face in front (dark eyes, a nose) and dark hair behind,
/// a spear in its right hand and a red shield with a gold rim and boss on its left arm.
fn statue_parts() -> Vec<Part> {
    let column = |f, s, r0, r1, z0, z1| Solid::Column {
        f,
        s,
        r0,
        r1,
        z0,
        z1,
    };
    let ball = |f, s, z, r| Solid::Ball { f, s, z, r };
    vec![
        // Eyes and nose.
        Part {
            solid: ball(3.0, 1.3, 41.0, 0.65),
            paint: |_| [30.0, 30.0, 45.0],
        },
        Part {
            solid: ball(3.0, -1.3, 41.0, 0.65),
            paint: |_| [30.0, 30.0, 45.0],
        },
        Part {
            solid: ball(3.55, 0.0, 40.0, 0.8),
            paint: |_| [225.0, 185.0, 150.0],
        },
        // Head: the face in front, hair behind and on top.
        Part {
            solid: ball(0.0, 0.0, 40.5, 3.6),
            paint: |[f, _, z]| if z > 42.6 || f < 0.8 { HAIR } else { SKIN },
        },
        Part {
            solid: column(0.0, 0.0, 1.6, 1.6, 35.5, 37.5),
            paint: |_| SKIN,
        },
        // The spear in the right hand: steel tip, wooden shaft.
        Part {
            solid: column(2.2, 6.6, 1.3, 0.0, 42.0, 47.0),
            paint: |_| [225.0, 225.0, 235.0],
        },
        Part {
            solid: column(2.2, 6.6, 0.6, 0.6, 7.0, 42.0),
            paint: |_| [130.0, 85.0, 40.0],
        },
        Part {
            solid: ball(2.2, 6.6, 23.5, 1.3),
            paint: |_| SKIN,
        },
        Part {
            solid: column(0.8, 6.1, 1.4, 1.4, 23.0, 34.5),
            paint: |_| ROBE,
        },
        // The shield on the left arm: a gold boss and rim on red.
        Part {
            solid: ball(0.5, -8.9, 27.0, 1.3),
            paint: |_| GOLD,
        },
        Part {
            solid: Solid::Plate {
                f: 0.5,
                z: 27.0,
                r: 6.0,
                s0: -8.8,
                s1: -7.4,
            },
            paint: |[f, _, z]| {
                if (f - 0.5).hypot(z - 27.0) > 5.0 {
                    GOLD
                } else {
                    [185.0, 30.0, 30.0]
                }
            },
        },
        Part {
            solid: column(0.0, -6.0, 1.5, 1.5, 22.0, 34.5),
            paint: |_| ROBE,
        },
        // Breastplate, belt, robe, plinth.
        Part {
            solid: column(0.0, 0.0, 5.2, 5.6, 26.0, 35.5),
            paint: |_| [165.0, 170.0, 182.0],
        },
        Part {
            solid: column(0.0, 0.0, 5.0, 5.0, 24.5, 26.0),
            paint: |_| [200.0, 160.0, 60.0],
        },
        Part {
            solid: column(0.0, 0.0, 6.0, 4.8, 6.0, 24.5),
            paint: |_| ROBE,
        },
        Part {
            solid: column(0.0, 0.0, 9.0, 9.0, 0.0, 6.0),
            paint: |[_, _, z]| {
                let stone = [150.0, 144.0, 132.0];
                if z > 5.0 {
                    stone.map(|c| c * 1.15)
                } else {
                    stone
                }
            },
        },
    ]
}

/// Rotations of the statue.
pub const STATUE_ROTATIONS: u32 = 8;

/// The statue, 24×48, seen from the direction facing + `rotation`·45° (angles growing toward
/// +y, clockwise seen from above with y down): 0 shows its front (the face, the spear on the
/// image's left, the shield's edge on its right), 2 its right side (the spear nearest, facing
/// the image's right), 4 its back (the hair), 6 its left side (the shield face on). Drawn by
/// marching level rays through its parts, lit from its front left and above, so the back is
/// darker.
pub fn statue(rotation: u32) -> RgbaImage {
    let parts = statue_parts();
    let angle = rotation as f32 * std::f32::consts::FRAC_PI_4;
    // Toward the eye, the way the rays go, and the image's right, in the statue's frame.
    let eye = [angle.cos(), angle.sin()];
    let ray = [-eye[0], -eye[1]];
    let right = [-ray[1], ray[0]];
    let light = {
        let l: [f32; 3] = [0.8, -0.35, 0.5];
        let length = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
        l.map(|c| c / length)
    };
    const STEP: f32 = 0.125;
    const REACH: f32 = 12.0;
    RgbaImage::from_fn(STATUE_WIDTH, STATUE_HEIGHT, |x, y| {
        let u = x as f32 + 0.5 - STATUE_WIDTH as f32 / 2.0;
        let z = STATUE_HEIGHT as f32 - (y as f32 + 0.5);
        for step in 0..(2.0 * REACH / STEP) as u32 {
            let t = step as f32 * STEP - REACH;
            let p = [u * right[0] + t * ray[0], u * right[1] + t * ray[1], z];
            if p[0] * p[0] + p[1] * p[1] > REACH * REACH {
                continue;
            }
            for part in &parts {
                if let Some(n) = part.solid.normal_inside(p) {
                    let lit = n[0] * light[0] + n[1] * light[1] + n[2] * light[2];
                    return opaque(shade((part.paint)(p), 0.5 + 0.65 * lit.max(0.0)));
                }
            }
        }
        Rgba([0, 0, 0, 0])
    })
}
