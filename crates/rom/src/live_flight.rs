//! The fly-through with the world moving: the [`crate::flight`] path flown through a map's live
//! world, so the benchmark and the accuracy report draw doors opening, lifts riding and lights
//! changing, not only the map as drawn.
//!
//! The path is the map's fixed one; what the world adds is time. Each frame is one game tick:
//! the camera stands, as a player's body would, on its sector's live floor (its eye
//! [`flight::eye_z`] above it), and the world runs the game's own rules around that body
//! ([`World::touch`], [`World::tick`]): a touch door opens as it comes near, a door never closes
//! on it, a lift carries it. Where the next pose does not fit the live heights (a shut door, a
//! lift away from the landing the path goes on to), the camera waits, and uses what is in its
//! way (a door opens, a resting lift comes); on a resting lift it stands on, it uses the lift
//! once a visit and stands still while it rides it down and back up.
//!
//! Everything is the world's integer state and the path's integer poses: the ROM and the host
//! fly the same frames.

use core::iter::Peekable;

use portalcast_format::{MapTables, MOVER_LIFT};

use crate::flight::{self, Flight};
use portalcast::player::Player;
use portalcast::render::view::Camera;
use portalcast::world::{body_only_in, Phase, World};

/// Frames the camera waits for its way to clear before it flies on regardless (a mover that
/// never opens: in practice a wait ends in under 300).
pub const MAX_WAIT_FRAMES: u32 = 1024;

/// The fly-through of one map through its live world, one frame at a time.
#[derive(Clone, Debug)]
pub struct LiveFlight<'m> {
    map: &'m MapTables<'m>,
    path: Peekable<Flight<'m>>,
    camera: Camera,
    /// Frames flown (the world's ticks).
    frame: u32,
    /// Frames waited for the next pose to fit.
    waited: u32,
    /// The lift the camera used on this visit to its sector, if it did.
    ridden: Option<u16>,
}

impl<'m> LiveFlight<'m> {
    /// The fly-through of `map` at its first frame, with `world` restarted for it. Not
    /// inlined, nor is [`LiveFlight::advance`]: on the GBA their temporaries (a flight is half a
    /// kilobyte) would sit in the caller's frame, under the renderer's.
    #[inline(never)]
    pub fn new<const S: usize, const M: usize, const T: usize>(
        map: &'m MapTables<'m>,
        world: &mut World<S, M, T>,
    ) -> LiveFlight<'m> {
        world.restart(map);
        let mut path = Flight::new(map).peekable();
        let camera = path.next().expect("a flight never ends");
        let mut flight = LiveFlight {
            map,
            path,
            camera,
            frame: 0,
            waited: 0,
            ridden: None,
        };
        flight.stand(world);
        flight
    }

    /// The camera of this frame.
    pub fn camera(&self) -> Camera {
        self.camera
    }

    /// Frames flown so far: the game tick of this frame.
    pub fn frame(&self) -> u32 {
        self.frame
    }

    /// On to the next frame: the camera flies on if its next pose fits the live heights (else
    /// waits, using what is in its way), then the world runs a tick around its body.
    #[inline(never)]
    pub fn advance<const S: usize, const M: usize, const T: usize>(
        &mut self,
        world: &mut World<S, M, T>,
    ) {
        let map = self.map;
        let next = *self.path.peek().expect("a flight never ends");
        let riding = world
            .mover_index(map, self.camera.sector)
            .is_some_and(|index| {
                map.movers[index].kind == MOVER_LIFT
                    && world.movers()[index].phase != Phase::Resting
            });
        if !riding && (self.waited >= MAX_WAIT_FRAMES || self.fits(world, &next)) {
            self.path.next();
            self.camera = next;
            self.waited = 0;
        } else {
            self.waited += 1;
            if let Some(index) = world.mover_index(map, next.sector) {
                if world.movers()[index].phase == Phase::Resting
                    || world.movers()[index].phase == Phase::Back
                {
                    world.use_mover(map, index);
                }
            }
        }
        if self
            .ridden
            .is_some_and(|sector| sector != self.camera.sector)
        {
            self.ridden = None;
        }
        if self.ridden.is_none() {
            // Used once the body is on the lift alone: from its edge, the landing beside it
            // would turn the lift back at once.
            if let Some(index) = world.mover_index(map, self.camera.sector) {
                if map.movers[index].kind == MOVER_LIFT
                    && world.movers()[index].phase == Phase::Resting
                    && body_only_in(map, self.camera.sector, self.camera.position)
                {
                    world.use_mover(map, index);
                    self.ridden = Some(self.camera.sector);
                }
            }
        }
        let body = self.body(world);
        world.touch(map, &body);
        world.tick(map, &body);
        self.frame += 1;
        self.stand(world);
    }

    /// Whether the camera may fly to `next`: within its sector always (the world keeps a mover
    /// off the body there); into another, when the live heights let a walker pass.
    fn fits<const S: usize, const M: usize, const T: usize>(
        &self,
        world: &World<S, M, T>,
        next: &Camera,
    ) -> bool {
        if next.sector == self.camera.sector {
            return true;
        }
        let live = world.map(self.map);
        flight::passable(
            &live,
            &live.sectors[usize::from(self.camera.sector)],
            &live.sectors[usize::from(next.sector)],
            next.position,
        )
    }

    /// The camera's body: a player standing at the camera on its sector's live floor.
    fn body<const S: usize, const M: usize, const T: usize>(
        &self,
        world: &World<S, M, T>,
    ) -> Player {
        Player::standing_at(
            &world.map(self.map),
            self.camera.sector,
            self.camera.position,
            self.camera.angle,
        )
    }

    /// The camera's eye on its sector's live floor, and the frame's lights set.
    fn stand<const S: usize, const M: usize, const T: usize>(
        &mut self,
        world: &mut World<S, M, T>,
    ) {
        world.show(self.map, self.frame);
        let live = world.map(self.map);
        self.camera.eye_z = flight::eye_z(
            &live,
            &live.sectors[usize::from(self.camera.sector)],
            self.camera.position,
        );
    }
}
