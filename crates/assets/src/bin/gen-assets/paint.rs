//! Procedural, deterministic painting of the shipped textures, sky and sprites.
//!
//! Everything here is drawn from fixed seeds with a small LCG and tileable value noise, so the
//! PNGs are reproducible byte for byte and tile seamlessly (noise periods divide the image
//! size). Looks favour strong contrast at low resolution: the GBA shows walls at 120×80.

use image::{Rgb, RgbImage, Rgba, RgbaImage};

/// Numerical Recipes' 64-bit LCG; plenty for texture speckle.
pub struct Lcg(u64);

impl Lcg {
    pub fn new(seed: u64) -> Lcg {
        Lcg(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0x2545_F491_4F6C_DD1D)
    }

    pub fn next_u32(&mut self) -> u32 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 33) as u32
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f32 {
        self.next_u32() as f32 / (1u64 << 31) as f32
    }
}

/// Value noise on a lattice of `period × period` cells that wraps, sampled over a
/// `size × size` image, smoothstep-interpolated, in `[0, 1]`.
struct TiledNoise {
    period: usize,
    values: Vec<f32>,
}

impl TiledNoise {
    fn new(period: usize, rng: &mut Lcg) -> TiledNoise {
        TiledNoise {
            period,
            values: (0..period * period).map(|_| rng.unit()).collect(),
        }
    }

    /// `u, v` in lattice units.
    fn at(&self, u: f32, v: f32) -> f32 {
        let p = self.period;
        let (x0, y0) = (u.floor(), v.floor());
        let (fx, fy) = (u - x0, v - y0);
        let (sx, sy) = (fx * fx * (3.0 - 2.0 * fx), fy * fy * (3.0 - 2.0 * fy));
        let wrap = |i: f32| (i as i64).rem_euclid(p as i64) as usize;
        let (x0, y0) = (wrap(x0), wrap(y0));
        let (x1, y1) = ((x0 + 1) % p, (y0 + 1) % p);
        let value = |x: usize, y: usize| self.values[y * p + x];
        let top = value(x0, y0) + (value(x1, y0) - value(x0, y0)) * sx;
        let bottom = value(x0, y1) + (value(x1, y1) - value(x0, y1)) * sx;
        top + (bottom - top) * sy
    }
}

/// Fractal noise that tiles horizontally over `width` texels (and vertically too when sampled
/// over a square image, or with integer multiples of the texel coordinates): octave `k` has
/// `base << k` lattice cells across the width, amplitudes halving. Result in `[0, 1]`.
struct Fractal {
    octaves: Vec<(TiledNoise, f32)>,
    texels_per_cell: f32,
}

impl Fractal {
    fn new(base: usize, octaves: usize, width: u32, rng: &mut Lcg) -> Fractal {
        let octaves = (0..octaves)
            .map(|k| (TiledNoise::new(base << k, rng), 0.5f32.powi(k as i32)))
            .collect();
        Fractal {
            octaves,
            texels_per_cell: width as f32 / base as f32,
        }
    }

    fn at(&self, x: f32, y: f32) -> f32 {
        let mut sum = 0.0;
        let mut total = 0.0;
        let mut scale = 1.0 / self.texels_per_cell;
        for (noise, amplitude) in &self.octaves {
            sum += noise.at(x * scale, y * scale) * amplitude;
            total += amplitude;
            scale *= 2.0;
        }
        sum / total
    }
}

fn clamp_byte(value: f32) -> u8 {
    value.round().clamp(0.0, 255.0) as u8
}

/// `colour * factor`, per channel, clamped.
pub(crate) fn shade(colour: [f32; 3], factor: f32) -> Rgb<u8> {
    Rgb(colour.map(|c| clamp_byte(c * factor)))
}

pub(crate) fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t.clamp(0.0, 1.0))
}

const SIZE: u32 = 64;

/// Courses of red-brown bricks, 32×16, with light mortar and per-brick tone.
pub fn brick() -> RgbImage {
    let mut rng = Lcg::new(1);
    let grain = Fractal::new(8, 3, SIZE, &mut rng);
    let tones: Vec<f32> = (0..16).map(|_| 0.8 + 0.35 * rng.unit()).collect();
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let course = y / 16;
        let shifted = x + if course % 2 == 1 { 16 } else { 0 };
        let (bx, by) = (shifted % 32, y % 16);
        let n = grain.at(x as f32, y as f32);
        if by < 2 || bx < 2 {
            return shade([190.0, 185.0, 170.0], 0.75 + 0.4 * n);
        }
        let tone = tones[((shifted / 32) % 2 + course * 2) as usize % 16];
        // A darker lower-right lip gives each brick some depth.
        let lip = if by >= 14 || bx >= 30 { 0.7 } else { 1.0 };
        shade([170.0, 62.0, 40.0], tone * lip * (0.7 + 0.5 * n))
    })
}

/// Large grey blocks in staggered courses, with cracks.
pub fn stone() -> RgbImage {
    let mut rng = Lcg::new(2);
    let grain = Fractal::new(4, 4, SIZE, &mut rng);
    let cracks = Fractal::new(8, 2, SIZE, &mut rng);
    let tones: Vec<f32> = (0..8).map(|_| 0.8 + 0.3 * rng.unit()).collect();
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let course = y / 32;
        let shifted = (x + course * 24) % SIZE;
        let (bx, by) = (shifted % 32, y % 32);
        let n = grain.at(x as f32, y as f32);
        if by < 2 || bx < 2 {
            return shade([60.0, 60.0, 66.0], 0.8 + 0.3 * n);
        }
        let tone = tones[((shifted / 32) + course * 2) as usize % 8];
        let crack = (cracks.at(x as f32, y as f32) - 0.5).abs() < 0.02;
        let edge = if by < 4 || bx < 4 { 1.15 } else { 1.0 };
        let factor = tone * edge * (0.65 + 0.55 * n) * if crack { 0.55 } else { 1.0 };
        shade([140.0, 140.0, 150.0], factor)
    })
}

/// Vertical planks with grain and dark gaps.
pub fn wood() -> RgbImage {
    let mut rng = Lcg::new(3);
    let grain = Fractal::new(4, 3, SIZE, &mut rng);
    let tones: Vec<f32> = (0..4).map(|_| 0.8 + 0.3 * rng.unit()).collect();
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let plank = x / 16;
        let px = x % 16;
        if px == 0 {
            return Rgb([40, 24, 12]);
        }
        let n = grain.at(x as f32 * 4.0, y as f32);
        let rings = ((px as f32 * 0.9 + n * 6.0 + plank as f32 * 2.0).sin() * 0.5 + 0.5) * 0.3;
        let knot = if (y + plank * 23) % 64 == 40 && px > 5 && px < 11 {
            0.6
        } else {
            1.0
        };
        shade(
            [150.0, 96.0, 52.0],
            tones[plank as usize] * (0.75 + rings) * knot,
        )
    })
}

/// Blue-grey plates with seams, rivets and brushed streaks.
pub fn metal() -> RgbImage {
    let mut rng = Lcg::new(4);
    let streaks = Fractal::new(1, 3, SIZE, &mut rng);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let (px, py) = (x % 32, y % 32);
        let n = streaks.at(x as f32, y as f32 * 8.0);
        if px == 0 || py == 0 {
            return Rgb([30, 34, 42]);
        }
        if px == 1 || py == 1 {
            return Rgb([170, 180, 196]);
        }
        let rivet = [(5, 5), (26, 5), (5, 26), (26, 26)]
            .iter()
            .any(|&(rx, ry)| (px as i32 - rx).pow(2) + (py as i32 - ry).pow(2) <= 3);
        if rivet {
            return if px < 16 && py < 16 || px >= 16 && py >= 16 {
                Rgb([210, 216, 226])
            } else {
                Rgb([190, 196, 210])
            };
        }
        shade([100.0, 112.0, 130.0], 0.8 + 0.4 * n)
    })
}

/// Checkered cream and terracotta floor tiles, 16×16, with grout.
pub fn tiles() -> RgbImage {
    let mut rng = Lcg::new(5);
    let grain = Fractal::new(8, 2, SIZE, &mut rng);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let n = grain.at(x as f32, y as f32);
        if x % 16 == 0 || y % 16 == 0 {
            return shade([80.0, 70.0, 60.0], 0.9 + 0.2 * n);
        }
        let dark = ((x / 16) + (y / 16)) % 2 == 1;
        let colour = if dark {
            [176.0, 84.0, 52.0]
        } else {
            [226.0, 210.0, 170.0]
        };
        shade(colour, 0.85 + 0.25 * n)
    })
}

/// Grass: green fractal noise with light blades.
pub fn grass() -> RgbImage {
    let mut rng = Lcg::new(6);
    let patches = Fractal::new(4, 4, SIZE, &mut rng);
    let blades: Vec<bool> = (0..SIZE * SIZE).map(|_| rng.unit() < 0.08).collect();
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let n = patches.at(x as f32, y as f32);
        let colour = mix([40.0, 90.0, 30.0], [100.0, 150.0, 50.0], n * 1.4 - 0.2);
        let blade = blades[(y * SIZE + x) as usize];
        shade(colour, if blade { 1.35 } else { 0.8 + 0.3 * n })
    })
}

/// Dirt: brown noise with pebbles.
pub fn dirt() -> RgbImage {
    let mut rng = Lcg::new(7);
    let ground = Fractal::new(4, 4, SIZE, &mut rng);
    let pebbles: Vec<(i32, i32, i32)> = (0..14)
        .map(|_| {
            (
                (rng.unit() * 64.0) as i32,
                (rng.unit() * 64.0) as i32,
                2 + (rng.unit() * 2.0) as i32,
            )
        })
        .collect();
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let n = ground.at(x as f32, y as f32);
        let on_pebble = pebbles.iter().find(|&&(px, py, r)| {
            let dx = (x as i32 - px + 96).rem_euclid(64) - 32;
            let dy = (y as i32 - py + 96).rem_euclid(64) - 32;
            dx * dx + dy * dy <= r * r
        });
        match on_pebble {
            Some(&(px, py, _)) => {
                let lit = (x as i32) < px || (y as i32) < py;
                shade([150.0, 140.0, 125.0], if lit { 1.1 } else { 0.8 })
            }
            None => shade([110.0, 76.0, 46.0], 0.7 + 0.5 * n),
        }
    })
}

/// Stair risers: a bright nosing band every 16 rows over a darker face.
pub fn step() -> RgbImage {
    let mut rng = Lcg::new(8);
    let grain = Fractal::new(8, 2, SIZE, &mut rng);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let n = grain.at(x as f32, y as f32);
        let row = y % 16;
        let factor = match row {
            0 => 1.5,
            1..=2 => 1.25,
            3 => 0.5,
            _ => 0.75 - row as f32 * 0.015,
        };
        shade([170.0, 160.0, 140.0], factor * (0.85 + 0.3 * n))
    })
}

/// An ornamental band: gold diamonds on dark red, for sills, lintels and upper strips.
pub fn trim() -> RgbImage {
    let mut rng = Lcg::new(9);
    let grain = Fractal::new(8, 2, SIZE, &mut rng);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let n = grain.at(x as f32, y as f32);
        let (cx, cy) = ((x % 16) as i32 - 8, (y % 16) as i32 - 8);
        let diamond = cx.abs() + cy.abs();
        if y % 32 < 2 {
            return shade([220.0, 180.0, 80.0], 0.9 + 0.2 * n);
        }
        match diamond {
            0..=4 => shade([230.0, 190.0, 70.0], 0.9 + 0.2 * n),
            5 => shade([120.0, 90.0, 30.0], 1.0),
            _ => shade([110.0, 28.0, 30.0], 0.8 + 0.3 * n),
        }
    })
}

/// Plaster ceiling panels with dark beams.
pub fn ceiling() -> RgbImage {
    let mut rng = Lcg::new(10);
    let grain = Fractal::new(8, 3, SIZE, &mut rng);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let n = grain.at(x as f32, y as f32);
        let (px, py) = (x % 32, y % 32);
        if px < 3 || py < 3 {
            return shade([70.0, 50.0, 36.0], 0.8 + 0.3 * n);
        }
        let bevel = if px == 3 || py == 3 { 0.7 } else { 1.0 };
        shade([200.0, 196.0, 184.0], bevel * (0.85 + 0.2 * n))
    })
}

/// Water: blue with bright wave crests.
pub fn water() -> RgbImage {
    let mut rng = Lcg::new(11);
    let waves = Fractal::new(4, 3, SIZE, &mut rng);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let n = waves.at(x as f32, y as f32);
        let crest = ((y as f32 / 64.0 * std::f32::consts::TAU * 4.0 + n * 8.0).sin() + 1.0) * 0.5;
        let colour = mix([20.0, 50.0, 110.0], [90.0, 160.0, 210.0], crest.powi(6));
        shade(colour, 0.85 + 0.3 * n)
    })
}

/// White marble with grey veins.
pub fn marble() -> RgbImage {
    let mut rng = Lcg::new(12);
    let veins = Fractal::new(2, 5, SIZE, &mut rng);
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let n = veins.at(x as f32, y as f32);
        let vein = ((x as f32 + y as f32) / 64.0 * std::f32::consts::TAU + n * 10.0)
            .sin()
            .abs();
        let colour = mix(
            [120.0, 118.0, 130.0],
            [235.0, 232.0, 225.0],
            vein.powf(0.35),
        );
        shade(colour, 1.0)
    })
}

/// Every shipped texture: (file stem, image).
pub fn textures() -> Vec<(&'static str, RgbImage)> {
    vec![
        ("brick", brick()),
        ("ceiling", ceiling()),
        ("dirt", dirt()),
        ("grass", grass()),
        ("marble", marble()),
        ("metal", metal()),
        ("step", step()),
        ("stone", stone()),
        ("tiles", tiles()),
        ("trim", trim()),
        ("water", water()),
        ("wood", wood()),
    ]
}

/// Sky panorama width: one full turn. 512 texels is close to one texel per screen column at a
/// 90° field of view over 120 columns (480 per turn).
pub const SKY_WIDTH: u32 = 512;
/// One texel per screen line: the renderer maps the horizon to the middle row, and the view spans
/// at most 80 + 40 lines (half a screen plus the look limit) either side of it, so 256 rows (a
/// power of two, as the column kernel needs) cover every row at every look angle.
pub const SKY_HEIGHT: u32 = 256;
/// Row of the horizon: the middle, where the view centre falls when looking straight ahead.
const HORIZON: f32 = 128.0;

/// A seamless 360° panorama: gradient sky with clouds, and two ranges of hills at the horizon.
pub fn sky() -> RgbImage {
    let mut rng = Lcg::new(20);
    let clouds = Fractal::new(8, 5, SKY_WIDTH, &mut rng);
    let far = Fractal::new(6, 4, SKY_WIDTH, &mut rng);
    let near = Fractal::new(4, 4, SKY_WIDTH, &mut rng);
    RgbImage::from_fn(SKY_WIDTH, SKY_HEIGHT, |x, y| {
        let (xf, yf) = (x as f32, y as f32);
        let far_top = HORIZON - 6.0 - 34.0 * far.at(xf, 0.0);
        let near_top = HORIZON + 4.0 - 26.0 * near.at(xf, 100.0);
        if yf >= near_top {
            let depth = ((yf - near_top) / 40.0).min(1.0);
            return shade(mix([50.0, 90.0, 45.0], [25.0, 45.0, 25.0], depth), 1.0);
        }
        if yf >= far_top {
            return shade(
                [80.0, 100.0, 130.0],
                0.9 + 0.2 * (1.0 - (yf - far_top) / 40.0),
            );
        }
        let height = (yf / HORIZON).clamp(0.0, 1.0);
        let base = mix([30.0, 70.0, 170.0], [170.0, 200.0, 235.0], height * height);
        // Clouds thin out toward the horizon and are squashed into horizontal streaks.
        let c = clouds.at(xf, yf * 2.5);
        let cover = ((c - 0.52) * 4.0).clamp(0.0, 1.0) * (1.0 - height * 0.6);
        shade(mix(base, [245.0, 245.0, 250.0], cover), 1.0)
    })
}

/// A standing torch, 16×48: an iron pole and bracket with a flame; transparent around it.
pub fn torch() -> RgbaImage {
    let clear = Rgba([0, 0, 0, 0]);
    RgbaImage::from_fn(16, 48, |x, y| {
        let (xf, yf) = (x as f32 + 0.5, y as f32 + 0.5);
        let dx = xf - 8.0;
        // Flame: a teardrop from y 2 to 16, white-yellow core fading to red.
        if (2.0..16.0).contains(&yf) {
            let t = (yf - 2.0) / 14.0;
            let half_width = 5.0 * (t * std::f32::consts::PI).sin().powf(0.7) * (0.4 + 0.6 * t);
            if dx.abs() <= half_width {
                let core = 1.0 - dx.abs() / half_width.max(0.01);
                let colour = mix([220.0, 50.0, 20.0], [255.0, 240.0, 150.0], core * t + 0.2);
                let Rgb([r, g, b]) = shade(colour, 1.0);
                return Rgba([r, g, b, 255]);
            }
            return clear;
        }
        // Bowl.
        if (16.0..20.0).contains(&yf) && dx.abs() <= 5.0 - (yf - 16.0) {
            return Rgba([90, 80, 70, 255]);
        }
        // Pole with a highlight, and a base plate.
        if yf >= 20.0 && dx.abs() <= 1.5 {
            return if dx < 0.0 {
                Rgba([120, 110, 100, 255])
            } else {
                Rgba([60, 55, 50, 255])
            };
        }
        if yf >= 45.0 && dx.abs() <= 5.0 {
            return Rgba([70, 64, 58, 255]);
        }
        clear
    })
}

/// A stone column, 24×64: a shaft 20 wide, shaded as a cylinder lit from the left and speckled,
/// between a capital and a base the full width with rounded corners; opaque but for the
/// corners and the two texels either side of the shaft.
pub fn pillar() -> RgbaImage {
    const WIDTH: u32 = 24;
    const HEIGHT: u32 = 64;
    let mut rng = Lcg::new(30);
    let speckle: Vec<f32> = (0..WIDTH * HEIGHT).map(|_| rng.unit()).collect();
    let stone = [150.0, 144.0, 132.0];
    RgbaImage::from_fn(WIDTH, HEIGHT, |x, y| {
        let xf = x as f32 + 0.5;
        let grain = 0.92 + 0.16 * speckle[(y * WIDTH + x) as usize];
        // Capital (rows 0..6) and base (rows 58..64): full width, a rim line, round corners.
        let slab = |top: u32, bottom: u32| -> Option<Rgba<u8>> {
            if !(top..bottom).contains(&y) {
                return None;
            }
            let corner = (y == top || y + 1 == bottom) && (x == 0 || x + 1 == WIDTH);
            if corner {
                return Some(Rgba([0, 0, 0, 0]));
            }
            let rim = if y == top || y + 1 == bottom {
                0.75
            } else {
                1.0
            };
            let light = 1.05 - 0.3 * (xf / WIDTH as f32);
            let Rgb([r, g, b]) = shade(stone, light * rim * grain);
            Some(Rgba([r, g, b, 255]))
        };
        if let Some(texel) = slab(0, 6).or_else(|| slab(58, 64)) {
            return texel;
        }
        // Shaft: columns 2..22, lit from the left (cosine across the cylinder), with fluting
        // every 4 texels.
        let dx = (xf - 12.0) / 10.0;
        if dx.abs() > 1.0 {
            return Rgba([0, 0, 0, 0]);
        }
        let facing = (1.0 - dx * dx).sqrt();
        let light = 0.35 + 0.75 * facing * (1.0 - 0.4 * dx);
        let flute = if x % 4 == 1 { 0.82 } else { 1.0 };
        let Rgb([r, g, b]) = shade(stone, light * flute * grain);
        Rgba([r, g, b, 255])
    })
}

/// A hanging lamp, 16×24: a chain of links down the middle (rows 0..9), an iron cap, a
/// glowing glass body in an iron frame, and a finial below; transparent around it.
pub fn lamp() -> RgbaImage {
    let clear = Rgba([0, 0, 0, 0]);
    let iron = |light: f32| {
        let Rgb([r, g, b]) = shade([70.0, 64.0, 60.0], light);
        Rgba([r, g, b, 255])
    };
    RgbaImage::from_fn(16, 24, |x, y| {
        let dx = x as f32 + 0.5 - 8.0;
        // Chain: alternate links, an upright one (2 texels wide, hollow middle) and a side-on
        // one (a single texel), 3 rows each.
        if y < 9 {
            let link = y / 3;
            let row = y % 3;
            return if link % 2 == 0 {
                // A ring: 2 texels across at its top and bottom, open in the middle row.
                match (row, x) {
                    (1, 6) => iron(1.4),
                    (1, 9) => iron(0.8),
                    (0 | 2, 7) => iron(1.3),
                    (0 | 2, 8) => iron(1.0),
                    _ => clear,
                }
            } else if x == 7 || x == 8 {
                iron(if x == 7 { 1.2 } else { 0.8 })
            } else {
                clear
            };
        }
        // Cap: a trapezoid widening from 4 to 12 texels over rows 9..12.
        if y < 12 {
            let half = 2.0 + 2.0 * (y - 9) as f32 + 1.0;
            return if dx.abs() <= half {
                iron(1.1 - 0.03 * dx)
            } else {
                clear
            };
        }
        // Body: rows 12..21, 12 wide; iron frame at the edges and the middle bar, glass glowing
        // brightest at its centre.
        if y < 21 {
            if dx.abs() > 6.0 {
                return clear;
            }
            if dx.abs() > 5.0 || y == 12 || y == 20 {
                return iron(0.9);
            }
            let dy = (y as f32 + 0.5 - 16.5) / 4.5;
            let glow = (1.0 - (dx / 5.0).powi(2) * 0.6 - dy * dy * 0.4).clamp(0.0, 1.0);
            let colour = mix([200.0, 110.0, 30.0], [255.0, 245.0, 180.0], glow);
            let Rgb([r, g, b]) = shade(colour, 1.0);
            return Rgba([r, g, b, 255]);
        }
        // Finial: narrowing to a point.
        let half = 3.0 - 1.2 * (y - 21) as f32;
        if dx.abs() <= half.max(0.5) {
            iron(0.8)
        } else {
            clear
        }
    })
}

/// A grate for a portal's opening, 32×64: four upright iron bars 3 texels wide, 8 apart, so the
/// image tiles across a wide opening; a frame across the top and the bottom and a crossbar at
/// mid-height, riveted where the bars cross them; transparent between the bars.
pub fn grate() -> RgbaImage {
    const WIDTH: u32 = 32;
    const HEIGHT: u32 = 64;
    let clear = Rgba([0, 0, 0, 0]);
    let iron = |light: f32| {
        let Rgb([r, g, b]) = shade([78.0, 72.0, 68.0], light);
        Rgba([r, g, b, 255])
    };
    RgbaImage::from_fn(WIDTH, HEIGHT, |x, y| {
        // Texel across a bar: 0, 1, 2 in the bar (lit from the left), else between bars.
        let across = (x + 6) % 8;
        let bar = across < 3;
        let rail = |top: u32, rows: u32| (top..top + rows).contains(&y);
        let (frame_top, frame_bottom, crossbar) = (rail(0, 4), rail(HEIGHT - 4, 4), rail(30, 3));
        if frame_top || frame_bottom || crossbar {
            // Flat strap: lit on its upper edge, shadowed on its lower one; a rivet on each bar.
            let (first, last) = if frame_top {
                (0, 3)
            } else if frame_bottom {
                (HEIGHT - 4, HEIGHT - 1)
            } else {
                (30, 32)
            };
            if bar && across == 1 && y == (first + last) / 2 {
                return iron(1.7);
            }
            let light = if y == first {
                1.35
            } else if y == last {
                0.6
            } else {
                1.0
            };
            return iron(light);
        }
        if !bar {
            return clear;
        }
        // A round bar: bright on its left, dark on its right, a little rust lower down.
        let light = [1.45, 1.0, 0.6][across as usize];
        let rust = (y as f32 / HEIGHT as f32) * 0.25;
        let Rgb([r, g, b]) = shade(mix([78.0, 72.0, 68.0], [120.0, 62.0, 34.0], rust), light);
        Rgba([r, g, b, 255])
    })
}

/// Leaded glass for a window's opening, 64×64, meant to be drawn translucent: diamond panes in
/// deep blue, ruby, amber, green and pale glass between lead cames, inside a lead frame; every
/// texel opaque. Each pane is one colour, brighter toward its upper left, with faint streaks.
pub fn window() -> RgbaImage {
    const SIDE: u32 = 64;
    /// Texels between the cames, along each diagonal.
    const PANE: i32 = 16;
    const GLASS: [[f32; 3]; 5] = [
        [40.0, 70.0, 190.0],
        [180.0, 30.0, 45.0],
        [225.0, 165.0, 40.0],
        [50.0, 150.0, 70.0],
        [190.0, 205.0, 215.0],
    ];
    let lead = |light: f32| {
        let Rgb([r, g, b]) = shade([58.0, 58.0, 66.0], light);
        Rgba([r, g, b, 255])
    };
    let mut rng = Lcg::new(0x5eed_0017);
    let streaks = Fractal::new(4, 3, SIDE, &mut rng);
    // A colour per pane, by its diagonal coordinates (at most 9 × 9 of them).
    let colours: Vec<usize> = (0..81)
        .map(|_| (rng.next_u32() % GLASS.len() as u32) as usize)
        .collect();
    RgbaImage::from_fn(SIDE, SIDE, |x, y| {
        let border = x.min(y).min(SIDE - 1 - x).min(SIDE - 1 - y);
        if border < 3 {
            return lead([1.3, 1.0, 0.7][border as usize]);
        }
        let (x, y) = (x as i32, y as i32);
        let (d1, d2) = (x + y, x - y + SIDE as i32);
        if d1 % PANE < 2 || d2 % PANE < 2 {
            return lead(if d1 % PANE == 0 || d2 % PANE == 0 {
                1.15
            } else {
                0.8
            });
        }
        let pane = (d1 / PANE) as usize * 9 + (d2 / PANE) as usize;
        // Within the pane: 0 at its upper-left came, 1 at its lower-right one.
        let inside =
            ((d1 % PANE) as f32 / PANE as f32 + 1.0 - (d2 % PANE) as f32 / PANE as f32) / 2.0;
        let light = 1.2 - 0.35 * inside + 0.25 * (streaks.at(x as f32 * 0.5, y as f32 * 2.0) - 0.5);
        let Rgb([r, g, b]) = shade(GLASS[colours[pane % colours.len()]], light);
        Rgba([r, g, b, 255])
    })
}
