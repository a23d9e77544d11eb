//! Deterministic camera poses for the accuracy tests.

use portalcast_format::MapTables;

use crate::geometry::{distance_to_segment, vertex, Vec2};
use crate::{angle_from_bits, find_sectors, Camera};

/// Closest a sampled eye comes to a wall, in world units.
const WALL_CLEARANCE: f64 = 2.0;
/// Eye height above the floor.
const EYE_HEIGHT: i32 = 32;
/// Least room left above the eye.
const HEAD_ROOM: i32 = 16;

/// `count` poses inside `map`, the same for the same `seed`.
///
/// Positions are uniform over the map's area (rejection sampling in the vertices' bounding
/// box), each strictly inside a sector and at least 2 units from every wall of it (so from
/// every wall of the map: the sector is convex). The eye is 32 above the floor (a slope's height under the
/// position), lowered to 16 under the ceiling in low sectors, and at mid-height where even that would be at or under the
/// floor. Angles are uniform over the turn. Every value is exactly representable by the engine:
/// positions are multiples of 1/256 (24.8), eye heights are multiples of 1/256, angles are
/// binary angles ([`Camera::angle_bits`] recovers them), so comparing with the engine measures
/// its rendering, not its quantisation of the pose. `sector` is always `Some`.
///
/// Returns fewer poses if no valid position turns up in `1000 · (count + 1)` tries (a map
/// without room for a clear eye).
pub fn sample_poses(map: &MapTables, count: usize, seed: u64) -> Vec<Camera> {
    let mut poses = Vec::with_capacity(count);
    if map.vertices.is_empty() || map.sectors.is_empty() {
        return poses;
    }
    let (mut min_x, mut min_y, mut max_x, mut max_y) = (i32::MAX, i32::MAX, i32::MIN, i32::MIN);
    for v in map.vertices {
        (min_x, min_y, max_x, max_y) = (
            min_x.min(v.x),
            min_y.min(v.y),
            max_x.max(v.x),
            max_y.max(v.y),
        );
    }
    let mut rng = Rng(seed);
    let mut tries = 1000 * (count + 1);
    while poses.len() < count && tries > 0 {
        tries -= 1;
        let x = on_fx8_grid(f64::from(min_x) + rng.unit() * f64::from(max_x - min_x));
        let y = on_fx8_grid(f64::from(min_y) + rng.unit() * f64::from(max_y - min_y));
        let angle = angle_from_bits(rng.next_u64() as u16);
        // Where layers overlap, any of the sectors holding the point (a draw only then, so
        // the poses of maps without layers are what they were).
        let holding = find_sectors(map, x, y);
        let pick = match holding.len() {
            0 | 1 => 0,
            n => rng.below(n as u64) as usize,
        };
        let Some(&sector_index) = holding.get(pick) else {
            continue;
        };
        let sector = &map.sectors[usize::from(sector_index)];
        let p = Vec2::new(x, y);
        let clear = map.sector_walls(sector).iter().all(|wall| {
            distance_to_segment(p, vertex(map, wall.start), vertex(map, wall.end)) >= WALL_CLEARANCE
        });
        if !clear {
            continue;
        }
        // In 24.8 bits: a sloped floor's height is a multiple of 1/256, exactly the engine's.
        let (floor, ceil) = map.heights_fx8_at(sector, (x * 256.0) as i32, (y * 256.0) as i32);
        let eye = (floor + EYE_HEIGHT * 256).min(ceil - HEAD_ROOM * 256);
        let eye_z = if eye > floor {
            f64::from(eye) / 256.0
        } else {
            f64::from((floor + ceil) >> 1) / 256.0
        };
        poses.push(Camera {
            x,
            y,
            eye_z,
            angle,
            sector: Some(sector_index),
        });
    }
    poses
}

/// The nearest multiple of 1/256.
fn on_fx8_grid(value: f64) -> f64 {
    (value * 256.0).round() / 256.0
}

/// SplitMix64: tiny, seedable, and the same on every host. The pose sampler's, and the
/// soak's (tests/emulator_soak.rs): a seeded run is the same run everywhere.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`, from the top 53 bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A number in `0..bound` (`bound > 0`; the modulo's bias is below 2^-40 for the small
    /// bounds it is used with).
    pub fn below(&mut self, bound: u64) -> u64 {
        self.next_u64() % bound
    }
}
