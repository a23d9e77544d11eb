//! The player: movement with collision, the jump, crouch and fly, looking up and down. It
//! produces the renderer's [`Camera`].
//!
//! The game runs at a fixed 60 ticks per second, one tick per VBlank, whatever the frame rate:
//! the ROM samples the buttons at every VBlank and runs [`Player::tick`] once for each sample
//! before it draws a frame. The player's state after a run is a function of the buttons of
//! each tick alone, identical on the GBA and on the host (integer arithmetic only), so a demo
//! is a key sequence and the host can replay what the ROM did.
//!
//! - [`input`]: buttons to [`Intent`] (the controls table is there and in the README).
//! - [`collide`]: the body as a disc against walls, portals and solid things, swept steps,
//!   sliding, exact sector tracking.
//! - [`vertical`]: standing, crouching, the jump parabola, falling, landing, flying.
//!
//! # Horizontal motion
//!
//! The velocity (24.8 bits per tick per axis) is multiplied by a friction factor each tick and
//! the d-pad adds an acceleration along the view (and the strafe direction), so the speed rises
//! to its limit in about a quarter of a second and falls back as fast: a d-pad is all or
//! nothing, and the ramp makes short taps move a little and holds move a lot. With friction
//! `f = 208/256` and acceleration `a`, the top speed is `a / (1 − f)`: 3 units per tick walking,
//! 6 running (180 and 360 units per second). In the air the friction is weaker and the
//! acceleration smaller in proportion (same top speed, little control). After the move the
//! velocity becomes the distance actually covered, so a wall takes away the speed into it and
//! keeps the speed along it.
//!
//! Turning ramps too: [`TURN_SLOW`] for the first [`TURN_RAMP_TICKS`] ticks of a press, for
//! aiming, then [`TURN_FAST`]; 36 ticks turn exactly 90°.

pub mod collide;
pub mod input;
pub mod vertical;

use portalcast_format::{MapTables, PlayerSize, Sector, NO_LINK, NO_SLOPE};

use crate::math::{Angle, Fx24_8, WorldPoint};
use crate::render::view::{Camera, MAX_LOOK_LINES};
use collide::{Body, Delta};
use input::Intent;
use vertical::STAND_EYE;

/// Friction on the ground and flying: the velocity keeps `GROUND_FRICTION / 256` per tick.
pub const GROUND_FRICTION: i32 = 208;
/// Friction in the air (jumping, falling).
pub const AIR_FRICTION: i32 = 248;
/// Acceleration walking, 24.8 bits per tick²: a top speed of 3 units per tick.
pub const WALK_ACCELERATION: i32 = 3 * 256 * (256 - GROUND_FRICTION) / 256;
/// Acceleration running: a top speed of 6 units per tick.
pub const RUN_ACCELERATION: i32 = 2 * WALK_ACCELERATION;
/// Highest speed per axis, 24.8 bits per tick, whatever pushes the player.
pub const SPEED_LIMIT: i32 = 16 * 256;
/// Turn per tick at the start of a press (binary angle units, 65536 per turn).
pub const TURN_SLOW: u16 = 256;
/// Turn per tick after the ramp: 2.1 s per full turn.
pub const TURN_FAST: u16 = 512;
/// Ticks of a turn press at [`TURN_SLOW`].
pub const TURN_RAMP_TICKS: u16 = 8;
/// Horizon rows per tick while looking up or down.
pub const LOOK_SPEED: i32 = 2;

/// Everything about the player that persists from tick to tick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Player {
    /// Centre of the body on the map plane.
    pub position: WorldPoint,
    /// The sector strictly containing [`Player::position`] that holds the feet: on a map with
    /// room over room, the one of the stack there whose heights the feet are within.
    pub sector: u16,
    /// The feet's sector when the last tick in a sector with a floor or ceiling portal ended
    /// ([`Player::eye_sector`]), or [`NO_LINK`].
    layered_feet: u16,
    /// The eye's sector then.
    layered_eye: u16,
    /// Horizontal velocity, 24.8 bits per tick (x, y).
    pub velocity: (i32, i32),
    /// View direction.
    pub angle: Angle,
    /// Height of the feet.
    pub feet_z: Fx24_8,
    /// Vertical speed of the feet per tick (up is positive).
    pub vertical_speed: Fx24_8,
    /// Height of the eye above the feet.
    pub eye_height: Fx24_8,
    /// The body the map gives the player (its standing eye, height and step).
    pub size: PlayerSize,
    /// Standing on the floor (not jumping, falling or flying).
    pub on_ground: bool,
    /// Fly mode: no gravity, A rises and B descends.
    pub fly: bool,
    /// Look up (positive) or down, as a horizon shift in 160-line screen rows.
    pub look_lines: i32,
    /// Ticks the current turn press has lasted.
    turn_ticks: u16,
    /// A jump started and A has not been released since.
    jump_latched: bool,
}

impl Player {
    /// A player standing still at the origin of no map, before [`Player::spawn`] puts it
    /// somewhere.
    pub const NOWHERE: Player = Player {
        position: WorldPoint::new(Fx24_8::ZERO, Fx24_8::ZERO),
        sector: 0,
        layered_feet: NO_LINK,
        layered_eye: NO_LINK,
        velocity: (0, 0),
        angle: Angle::from_bits(0),
        feet_z: Fx24_8::ZERO,
        vertical_speed: Fx24_8::ZERO,
        eye_height: Fx24_8::from_int(STAND_EYE),
        size: PlayerSize::NATIVE,
        on_ground: true,
        fly: false,
        look_lines: 0,
        turn_ticks: 0,
        jump_latched: false,
    };

    /// The player at the map's start: standing on the floor, looking straight ahead.
    pub fn spawn(map: &MapTables) -> Player {
        let start = map.player_start;
        Player::standing_at(
            map,
            start.sector,
            WorldPoint::new(
                Fx24_8::from_bits(start.x_fx8),
                Fx24_8::from_bits(start.y_fx8),
            ),
            Angle::from_bits(start.angle),
        )
    }

    /// The player standing still at `position`, which must lie strictly inside `sector`, with
    /// the map's body.
    pub fn standing_at(map: &MapTables, sector: u16, position: WorldPoint, angle: Angle) -> Player {
        let at = (position.x.to_bits(), position.y.to_bits());
        let (floor, _) = collide::heights_at(map.slopes, &map.sectors[usize::from(sector)], at);
        let size = map.player_start.size;
        Player {
            position,
            sector,
            layered_feet: sector,
            layered_eye: map.sector_at_height(sector, floor + size.eye_height * 256),
            angle,
            feet_z: Fx24_8::from_bits(floor),
            eye_height: Fx24_8::from_int(size.eye_height),
            size,
            ..Player::NOWHERE
        }
    }

    /// The eye's height.
    pub fn eye_z(&self) -> Fx24_8 {
        self.feet_z + self.eye_height
    }

    /// The sector holding the eye, which the view is drawn from: [`Player::sector`], or where
    /// the body reaches up through a floor or ceiling portal, the sector above it. Kept by the
    /// ticks in sectors with such portals only (a tick elsewhere stores nothing for it): their
    /// record stands while the feet are still in the sector it was made in.
    pub fn eye_sector(&self) -> u16 {
        if self.sector == self.layered_feet {
            self.layered_eye
        } else {
            self.sector
        }
    }

    /// Whether the eye is below the standing height (crouched, or held down by a ceiling).
    pub fn crouched(&self) -> bool {
        self.eye_height < Fx24_8::from_int(self.size.eye_height)
    }

    /// The body's vertical extent, for the collision rules, among `sectors` (their heights now).
    pub fn body<'s>(&self, sectors: &'s [Sector]) -> Body<'s> {
        Body {
            feet: self.feet_z,
            eye_height: self.eye_height,
            size: self.size,
            sectors,
        }
    }

    /// What the renderer needs.
    pub fn camera(&self) -> Camera {
        Camera {
            position: self.position,
            eye_z: self.eye_z(),
            angle: self.angle,
            sector: self.eye_sector(),
            look_lines: self.look_lines,
        }
    }

    /// Switches fly mode on or off. Off in the air, the player falls (from rest).
    pub fn toggle_fly(&mut self) {
        self.fly = !self.fly;
        self.on_ground = false;
        self.vertical_speed = Fx24_8::ZERO;
    }

    /// One tick (1/60 s) of `intent` on `map`, its sectors at the heights its table gives.
    pub fn tick(&mut self, intent: &Intent, map: &MapTables) {
        self.tick_among(intent, map, map.sectors);
    }

    /// One tick (1/60 s) of `intent` on `map`'s walls, among `sectors`: the same sectors with
    /// their heights now (a map with movers keeps them live, `crate::world`), so that the map's
    /// tables need no live copy every tick.
    ///
    /// In IWRAM on the GBA, with what it inlines (the turn, the acceleration, the vertical
    /// motion): the cartridge's fetches made this part of every tick cost about three times as
    /// much. The step's walk over nearby walls is in IWRAM too (`collide`); the rarer paths
    /// (pushes, portal crossings) stay in ROM.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram.player_tick")]
    pub fn tick_among(&mut self, intent: &Intent, map: &MapTables, sectors: &[Sector]) {
        if intent.toggle_fly {
            self.toggle_fly();
        }
        self.turn(intent.turn);
        self.look_lines = if intent.recentre {
            0
        } else {
            (self.look_lines + i32::from(intent.look) * LOOK_SPEED)
                .clamp(-MAX_LOOK_LINES, MAX_LOOK_LINES)
        };

        self.accelerate(intent);
        let (position, sector) = collide::slide(
            map,
            self.sector,
            self.position,
            Delta {
                x: self.velocity.0,
                y: self.velocity.1,
            },
            &self.body(sectors),
        );
        self.velocity = (
            position.x.to_bits() - self.position.x.to_bits(),
            position.y.to_bits() - self.position.y.to_bits(),
        );
        self.position = position;
        self.sector = sector;

        let here = &sectors[usize::from(sector)];
        // The sector's slope index and links before the map's tables: `map` need not be kept
        // for a flat sector (the two sit in one word of the sector).
        let heights = if here.slope == NO_SLOPE && here.links == 0 {
            (here.floor_z * 256, here.ceil_z * 256)
        } else if here.links == 0 {
            collide::heights_at(
                map.slopes,
                here,
                (position.x.to_bits(), position.y.to_bits()),
            )
        } else {
            self.rise_or_fall_in_layers(intent, map);
            return;
        };
        vertical::tick(self, intent, heights);
    }

    /// The vertical part of a tick in a sector with a floor or ceiling portal (room over room):
    /// the motion within the heights of the open space, then the sector of
    /// the stack that holds the feet, and the one that holds the eye. Out of line and in ROM,
    /// with its own copy of the vertical motion: only such sectors come here, and a second test
    /// of the sector's links after the motion made the compiler copy the motion into the IWRAM
    /// tick twice.
    #[inline(never)]
    #[cold]
    fn rise_or_fall_in_layers(&mut self, intent: &Intent, map: &MapTables) {
        let at = (self.position.x.to_bits(), self.position.y.to_bits());
        vertical::tick(self, intent, collide::open_heights_at(map, self.sector, at));
        self.sector = map.sector_at_height(self.sector, self.feet_z.to_bits());
        self.layered_feet = self.sector;
        self.layered_eye = map.sector_at_height(self.sector, self.eye_z().to_bits());
    }

    fn turn(&mut self, direction: i8) {
        if direction == 0 {
            self.turn_ticks = 0;
            return;
        }
        self.turn_ticks = self.turn_ticks.saturating_add(1);
        let rate = if self.turn_ticks <= TURN_RAMP_TICKS {
            TURN_SLOW
        } else {
            TURN_FAST
        };
        let step = Angle::from_bits(rate);
        self.angle = if direction > 0 {
            self.angle.wrapping_add(step)
        } else {
            self.angle.wrapping_sub(step)
        };
    }

    /// Friction, then the d-pad's acceleration along the view and the strafe direction.
    fn accelerate(&mut self, intent: &Intent) {
        let grounded = self.on_ground || self.fly;
        let friction = if grounded {
            GROUND_FRICTION
        } else {
            AIR_FRICTION
        };
        // Division truncates toward zero, so a coasting player comes to a full stop.
        let (vx, vy) = (
            self.velocity.0 * friction / 256,
            self.velocity.1 * friction / 256,
        );
        let mut acceleration = if intent.run {
            RUN_ACCELERATION
        } else {
            WALK_ACCELERATION
        };
        if !grounded {
            acceleration = acceleration * (256 - AIR_FRICTION) / (256 - GROUND_FRICTION);
        }
        if intent.forward != 0 && intent.strafe != 0 {
            // Diagonal: each part by 1/√2 (181/256), so it is no faster than straight.
            acceleration = acceleration * 181 / 256;
        }
        let forward = i32::from(intent.forward);
        let strafe = i32::from(intent.strafe);
        // Forward (cos, sin), right (−sin, cos); sine and cosine are 16.16 (±65536).
        let along = |unit_x: i32, unit_y: i32| {
            let x = (forward * unit_x - strafe * unit_y) * acceleration;
            let y = (forward * unit_y + strafe * unit_x) * acceleration;
            ((x + 32768) >> 16, (y + 32768) >> 16)
        };
        // Without the d-pad `along` is (0, 0) whatever the angle: no sine and cosine needed.
        let (ax, ay) = if forward == 0 && strafe == 0 {
            (0, 0)
        } else {
            let (sin, cos) = self.angle.sin_cos();
            along(cos.to_bits(), sin.to_bits())
        };
        self.velocity = (
            (vx + ax).clamp(-SPEED_LIMIT, SPEED_LIMIT),
            (vy + ay).clamp(-SPEED_LIMIT, SPEED_LIMIT),
        );
    }
}
