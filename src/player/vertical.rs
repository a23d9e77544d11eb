//! Vertical motion: standing and crouching, the jump, falling and landing, flying.
//!
//! The body's vertical state is the height of its feet, a vertical speed and the eye's height
//! above the feet. The heights are the map's [`PlayerSize`] (Doom maps have Doom's: eye 41,
//! height 56, steps of 24); the names below are native maps' values. Standing, the eye is
//! [`STAND_EYE`] above the floor; crouched,
//! [`CROUCH_EYE`]; the eye moves between the two at [`CROUCH_SPEED`] per tick, and never comes
//! closer than [`HEADROOM`](super::collide::HEADROOM) to the ceiling: under a low ceiling a player who lets go of crouch
//! stays as low as the ceiling demands.
//!
//! # The jump: an exact discrete parabola
//!
//! Every tick the feet move by the speed, then gravity takes [`GRAVITY`] off the speed. A jump
//! starts with [`JUMP_SPEED`] = `GRAVITY · JUMP_TICKS − GRAVITY / 2`, so after `k` ticks the
//! feet are `JUMP_SPEED·k − GRAVITY·k(k−1)/2 = GRAVITY·(JUMP_TICKS·k − k²/2)` up: the
//! parabola `h(t) = GRAVITY·(JUMP_TICKS·t − t²/2)` sampled at whole ticks, with no rounding
//! (all constants are whole 24.8 bits). Its apex is at `t = JUMP_TICKS`, a whole tick, where
//! `h = GRAVITY·JUMP_TICKS²/2 = JUMP_RISE` exactly: the eye reaches 32 + 16 = 48 above the floor
//! on tick 16 and lands back on the floor on tick 32, both exactly. (The thesis' formula has
//! gravity with the wrong sign, and its fall formula is a speed, not a height.)
//!
//! Falling uses the same gravity from a standing start (walking off a ledge), with the speed
//! capped at [`FALL_SPEED_MAX`]. A step down of at most [`STEP_UP_MAX`](super::collide::STEP_UP_MAX) is not a fall: the feet
//! follow the floor, so walking down stairs does not bounce. Entering a higher floor (a step up,
//! or a ledge reached at the top of a jump) puts the feet on it.
//!
//! # Flying
//!
//! Gravity is off; A rises and B descends at [`FLY_SPEED`]. The eye keeps [`HEADROOM`](super::collide::HEADROOM) below
//! the ceiling and the feet stay on or above the floor, so the eye is at least the eye height
//! above the floor. Leaving fly mode in the air starts a fall.

use portalcast_format::PlayerSize;

use super::input::Intent;
use super::Player;
use crate::math::Fx24_8;

/// Eye height above the feet standing, in world units, on native maps: a map's own is its
/// [`PlayerSize::eye_height`] (41 on Doom's).
pub const STAND_EYE: i32 = PlayerSize::NATIVE.eye_height;
/// Eye height above the feet crouched: also the least room the eye keeps above the floor.
pub const CROUCH_EYE: i32 = 16;
/// How much a jump lifts the feet at its apex: the standing eye goes from 32 to 48.
pub const JUMP_RISE: i32 = 16;
/// Ticks from the take-off to the apex (and as many back down).
pub const JUMP_TICKS: i32 = 16;
/// Speed lost per tick, in 24.8 bits per tick (1/8 unit per tick², 450 units/s² at 60 Hz):
/// `2·JUMP_RISE / JUMP_TICKS²`.
pub const GRAVITY: i32 = 2 * JUMP_RISE * 256 / (JUMP_TICKS * JUMP_TICKS);
/// Upward speed at take-off, in 24.8 bits per tick.
pub const JUMP_SPEED: i32 = GRAVITY * JUMP_TICKS - GRAVITY / 2;
/// Fastest fall, in 24.8 bits per tick (8 units per tick, half the radius).
pub const FALL_SPEED_MAX: i32 = 8 * 256;
/// Vertical speed flying, in 24.8 bits per tick (2 units per tick).
pub const FLY_SPEED: i32 = 2 * 256;
/// How fast the eye moves between standing and crouched, in 24.8 bits per tick.
pub const CROUCH_SPEED: i32 = 2 * 256;

// The parabola's constants are whole bits and reach the apex exactly.
const _: () = {
    assert!(2 * JUMP_RISE * 256 % (JUMP_TICKS * JUMP_TICKS) == 0 && GRAVITY % 2 == 0);
    let apex = JUMP_SPEED * JUMP_TICKS - GRAVITY * JUMP_TICKS * (JUMP_TICKS - 1) / 2;
    assert!(apex == JUMP_RISE * 256);
    // The last rising tick still rises, the next one falls: the apex is a single tick.
    assert!(JUMP_SPEED - GRAVITY * (JUMP_TICKS - 1) > 0);
    assert!(JUMP_SPEED - GRAVITY * JUMP_TICKS < 0);
};

/// The vertical part of one tick, after the horizontal move put the player where its sector's
/// floor and ceiling are `(floor, ceil)` (24.8 bits: a slope's under the player). Walking down
/// a slope is following the floor down, as a step down is: no fall, no jitter.
///
/// Inlined into the player's tick, which is in IWRAM: called out of line it ran from the
/// cartridge.
#[inline(always)]
pub fn tick(player: &mut Player, intent: &Intent, (floor, ceil): (i32, i32)) {
    let mut feet = player.feet_z.to_bits();
    let stand_eye = player.size.eye_height * 256;
    let headroom = player.size.headroom() * 256;
    let step_up = player.size.step_up * 256;

    // Most ticks: standing on this floor at full height, with room above, no crouch and no
    // jump. The code below then changes nothing but the jump latch (released) and the speed
    // (zero on the ground); this says so for a handful of tests.
    if player.on_ground
        && !player.fly
        && !intent.crouch
        && !intent.jump
        && feet == floor
        && player.eye_height.to_bits() == stand_eye
        && feet + stand_eye + headroom <= ceil
    {
        player.jump_latched = false;
        player.vertical_speed = Fx24_8::ZERO;
        return;
    }

    // A step up (or a ledge reached in the air): stand on the new floor.
    if feet < floor {
        feet = floor;
        if player.vertical_speed.to_bits() < 0 || player.on_ground {
            player.vertical_speed = Fx24_8::ZERO;
            player.on_ground = !player.fly;
        }
    }

    // The eye height: toward standing or crouched, below the ceiling's limit.
    let wants_crouch = intent.crouch && !player.fly;
    let target = if wants_crouch {
        CROUCH_EYE * 256
    } else {
        stand_eye
    };
    let mut eye = player.eye_height.to_bits();
    eye = if eye < target {
        (eye + CROUCH_SPEED).min(target)
    } else {
        (eye - CROUCH_SPEED).max(target)
    };
    eye = eye.min(ceil - headroom - feet).max(CROUCH_EYE * 256);

    if player.fly {
        let rise = i32::from(intent.jump) - i32::from(intent.crouch);
        feet += rise * FLY_SPEED;
        player.vertical_speed = Fx24_8::ZERO;
        player.on_ground = false;
    } else {
        if player.on_ground {
            if feet - floor > step_up {
                // Walked off a ledge: fall from rest.
                player.on_ground = false;
                player.vertical_speed = Fx24_8::ZERO;
            } else {
                // On the floor, or a step down: follow it.
                feet = floor;
            }
        }
        if player.on_ground && intent.jump && !player.jump_latched {
            player.on_ground = false;
            player.jump_latched = true;
            player.vertical_speed = Fx24_8::from_bits(JUMP_SPEED);
        }
        if !player.on_ground {
            let speed = player.vertical_speed.to_bits();
            feet += speed;
            player.vertical_speed = Fx24_8::from_bits((speed - GRAVITY).max(-FALL_SPEED_MAX));
        }
    }
    if !intent.jump {
        player.jump_latched = false;
    }

    // The eye keeps its room below the ceiling; the feet stay on or above the floor.
    if feet + eye + headroom > ceil {
        feet = ceil - headroom - eye;
        player.vertical_speed = Fx24_8::from_bits(player.vertical_speed.to_bits().min(0));
    }
    if feet <= floor {
        feet = floor;
        if !player.fly {
            player.on_ground = true;
            player.vertical_speed = Fx24_8::ZERO;
        }
    }
    player.feet_z = Fx24_8::from_bits(feet);
    player.eye_height = Fx24_8::from_bits(eye);
}
