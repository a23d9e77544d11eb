//! The world as it moves: the live heights of a map's moving sectors (doors, lifts, platforms,
//! crushers: [`portalcast_format::Mover`]), what starts them (the use button, walking into a
//! door, switches and walk-over lines: [`portalcast_format::Trigger`]), the switches' thrown
//! state, and the light of sectors that glow, strobe, flicker or are switched
//! ([`portalcast_format::Light`]).
//!
//! A map with movers or light effects gets a copy of its sector table, whose moving heights the
//! game's ticks change and whose effect lights each drawn frame sets ([`World::show`]); the
//! renderer, the collision code and the oracle read the frame's [`MapTables`] with that table in
//! place of the cartridge's ([`World::map`]), so each reads heights and light the one way it
//! always has. A copy of only the moving sectors would put a lookup on every height read, the
//! wall set-up's among them. A map without either keeps no copy.
//!
//! A glow, a strobe and a flicker are functions of the game's tick, so they are set once a
//! drawn frame rather than every tick: the same levels, for the frames anyone sees, at a
//! fraction of the cost. A switched light changes only when a trigger of its tag fires.
//!
//! Everything is integer and advances once a tick, so the host replays the ROM exactly.
//!
//! # The player is never crushed
//! A mover moves a tick only if the player's body, as the move would leave it, still fits every
//! sector its disc touches ([`Body::admits`](crate::player::collide::Body::admits), the rule the collision code keeps the body to): a
//! door or a crusher that would come down on the player goes back up, a lift that would lift the
//! player's head into its ceiling (or its floor past a step under a body beside it) goes back
//! down. A lift's floor carries a player standing on it.

use portalcast_format::{
    Light, MapTables, Mover, Sector, Thing, Trigger, LIGHT_FLICKER, LIGHT_GLOW, LIGHT_STROBE,
    LIGHT_SWITCHED, MOVER_CRUSHER, MOVER_DOOR, MOVER_LIFT, MOVER_ON_TOUCH, MOVER_ON_USE,
    MOVER_PLATFORM, STROBE_FLASH_TICKS, TRIGGER_LINE, TRIGGER_SWITCH, TRIGGER_THROWN,
};

use crate::math::{cross, Fx24_8, WorldPoint};
use crate::player::collide::{wall_points, RADIUS};
use crate::player::input::Intent;
use crate::player::Player;

/// How far in front of the eye the use button reaches, world units.
pub const USE_RANGE: i32 = 64;

/// How near (beyond the body's radius) a door that opens on touch opens, world units.
pub const TOUCH_REACH: i32 = 4;

/// Where a mover is in its cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// At its start height, until something starts it (doors and lifts).
    Resting,
    /// Moving from the start height to the other one.
    Away,
    /// At the other height, for the mover's wait.
    WaitingAway,
    /// Moving back to the start height.
    Back,
    /// At the start height, for the wait, before it goes again (platforms and crushers).
    WaitingHome,
}

/// One mover's live state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MoverState {
    /// The moving plane's height, world units.
    pub height: i32,
    /// Where it is in its cycle.
    pub phase: Phase,
    /// Ticks left of a wait.
    pub timer: u16,
}

impl MoverState {
    const IDLE: MoverState = MoverState {
        height: 0,
        phase: Phase::Resting,
        timer: 0,
    };

    /// The first of `movers` from index `from` on that is not resting. Over a slice, whose
    /// length LLVM does not know: a loop over `World::movers` itself was unrolled as many
    /// times as the ROM's maps have movers at most (12 on a Doom map), and the tick's code in
    /// VRAM has no room for that.
    #[inline(always)]
    fn next_moving(movers: &[MoverState], from: usize) -> Option<usize> {
        movers
            .iter()
            .skip(from)
            .position(|state| state.phase != Phase::Resting)
            .map(|offset| from + offset)
    }
}

/// The sector a [`World`] holds where it keeps no copy.
const NO_SECTOR: Sector = Sector {
    first_wall: 0,
    wall_count: 0,
    floor_z: 0,
    ceil_z: 0,
    floor_texture: 0,
    ceil_texture: 0,
    light: 0,
    links: 0,
    slope: portalcast_format::NO_SLOPE,
};

/// The trigger a [`World`] holds where it keeps no copy.
const NO_TRIGGER: Trigger = Trigger {
    wall: 0,
    tag: 0,
    kind: TRIGGER_SWITCH,
    thrown: 0,
    used_texture: 0,
};

/// The live state of one map: room for a sector table of `SECTORS` sectors, `MOVERS` movers'
/// states and a trigger table of `TRIGGERS` triggers (the ROM's: `assets::LIVE_SECTORS`,
/// `assets::LIVE_MOVERS` and `assets::LIVE_TRIGGERS`, the most of its maps with movers; all 0
/// where no map has any).
// `repr(C)`, the counters first and the sector-sized tables last: the ARM loads a field by an
// immediate offset under 4,096 bytes (a halfword under 256), so fields placed after a large
// map's sector table (a Doom map's 434 pieces: 8.7 KiB) would each cost extra instructions, and
// the tick's code in VRAM has no room for them.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub struct World<const SECTORS: usize, const MOVERS: usize, const TRIGGERS: usize> {
    /// Sectors of the map in [`World::sectors`]; 0 when the map has no movers.
    live: usize,
    /// Movers of the map in [`World::movers`].
    mover_count: usize,
    /// Triggers of the map in [`World::triggers`].
    trigger_count: usize,
    /// Switches thrown now: while there is any, each tick sees whether its movers are back.
    thrown: usize,
    /// The sector whose touch door [`World::touch_door`] is ([`NONE`]: none looked at yet).
    touch_sector: u16,
    /// The first door that opens on touch through a portal of [`World::touch_sector`]
    /// ([`NONE`]: none).
    touch_door: u16,
    /// The box, world units, outside which the body's centre cannot be within
    /// [`TOUCH_REACH`] of [`World::touch_door`]'s sector: most ticks end the touch test at it.
    touch_box: TouchBox,
    movers: [MoverState; MOVERS],
    /// Each mover's sector's box, as [`World::touch_box`].
    touch_boxes: [TouchBox; MOVERS],
    /// The map's triggers, its switches' [`Trigger::thrown`] live.
    triggers: [Trigger; TRIGGERS],
    /// Each live sector's first door that opens on touch through one of its portals
    /// ([`NONE`]: none): found once a map, for the ticks that cross into the sector.
    touch_doors: [u16; SECTORS],
    sectors: [Sector; SECTORS],
}

// The asset compiler leaves EWRAM for this much live state a sector, mover and trigger
// (`portalcast_format::memory::live_state_bytes`).
const _: () = {
    use core::mem::size_of;
    use portalcast_format::memory::{LIVE_MOVER_BYTES, LIVE_SECTOR_BYTES, LIVE_TRIGGER_BYTES};
    assert!(size_of::<Sector>() + size_of::<u16>() <= LIVE_SECTOR_BYTES);
    assert!(size_of::<MoverState>() + size_of::<TouchBox>() <= LIVE_MOVER_BYTES);
    assert!(size_of::<Trigger>() <= LIVE_TRIGGER_BYTES);
};

/// The index in `map.movers` of `sector`'s mover, if it moves (the movers are in the order of
/// their sectors).
fn mover_of(map: &MapTables, sector: u16) -> Option<usize> {
    map.movers.binary_search_by_key(&sector, |m| m.sector).ok()
}

/// An axis-aligned box, world units: `min_x, min_y, max_x, max_y`, bounds included.
type TouchBox = [i32; 4];

/// No sector, no mover.
const NONE: u16 = u16::MAX;

impl<const SECTORS: usize, const MOVERS: usize, const TRIGGERS: usize> Default
    for World<SECTORS, MOVERS, TRIGGERS>
{
    fn default() -> Self {
        World::new()
    }
}

/// The moving plane of `mover`: true for a floor (lifts, platforms), false for a ceiling.
fn moves_floor(mover: &Mover) -> bool {
    matches!(mover.kind, MOVER_LIFT | MOVER_PLATFORM)
}

/// Whether `mover` runs for ever (platforms, crushers) rather than when started.
fn runs_always(mover: &Mover) -> bool {
    matches!(mover.kind, MOVER_PLATFORM | MOVER_CRUSHER)
}

/// The height `mover` goes to from its start.
fn away_height(mover: &Mover) -> i32 {
    if mover.start == mover.low {
        mover.high
    } else {
        mover.low
    }
}

impl<const SECTORS: usize, const MOVERS: usize, const TRIGGERS: usize>
    World<SECTORS, MOVERS, TRIGGERS>
{
    /// A world for a map without movers.
    pub const fn new() -> World<SECTORS, MOVERS, TRIGGERS> {
        World {
            sectors: [NO_SECTOR; SECTORS],
            live: 0,
            movers: [MoverState::IDLE; MOVERS],
            mover_count: 0,
            triggers: [NO_TRIGGER; TRIGGERS],
            trigger_count: 0,
            thrown: 0,
            touch_sector: NONE,
            touch_door: NONE,
            touch_box: [0; 4],
            touch_doors: [NONE; SECTORS],
            touch_boxes: [[0; 4]; MOVERS],
        }
    }

    /// The world of `map` as it starts: every mover at its start height, the ones that run for
    /// ever already going.
    ///
    /// # Panics
    /// If `map` has more sectors than `SECTORS` and movers, or more movers than `MOVERS`.
    pub fn start(map: &MapTables) -> World<SECTORS, MOVERS, TRIGGERS> {
        let mut world = World::new();
        world.restart(map);
        world
    }

    /// [`World::start`] in place: a game switching maps keeps no second world on the stack
    /// (on the GBA, the stack's room is smaller than a map's live sector table).
    ///
    /// # Panics
    /// As [`World::start`].
    pub fn restart(&mut self, map: &MapTables) {
        self.live = 0;
        self.mover_count = 0;
        self.trigger_count = 0;
        self.thrown = 0;
        self.touch_sector = NONE;
        self.touch_door = NONE;
        self.touch_box = [0; 4];
        if map.movers.is_empty() && map.lights.is_empty() {
            return;
        }
        assert!(
            map.sectors.len() <= SECTORS
                && map.movers.len() <= MOVERS
                && map.triggers.len() <= TRIGGERS,
            "map '{}' has {} sectors, {} movers and {} triggers: the game keeps {SECTORS}, {MOVERS} and {TRIGGERS}",
            map.name,
            map.sectors.len(),
            map.movers.len(),
            map.triggers.len()
        );
        self.live = map.sectors.len();
        self.mover_count = map.movers.len();
        self.trigger_count = map.triggers.len();
        self.sectors[..self.live].copy_from_slice(map.sectors);
        self.triggers[..self.trigger_count].copy_from_slice(map.triggers);
        for (index, mover) in map.movers.iter().enumerate() {
            self.movers[index] = MoverState {
                height: mover.start,
                phase: if runs_always(mover) {
                    Phase::Away
                } else {
                    Phase::Resting
                },
                timer: 0,
            };
            self.set_height(mover, mover.start);
            self.touch_boxes[index] = reach_box(map, &map.sectors[usize::from(mover.sector)]);
        }
        for (slot, sector) in self.touch_doors.iter_mut().zip(map.sectors) {
            *slot = map
                .sector_walls(sector)
                .iter()
                .find_map(|wall| {
                    let index = mover_of(map, wall.neighbour()?)?;
                    (map.movers[index].flags & MOVER_ON_TOUCH != 0).then_some(index as u16)
                })
                .unwrap_or(NONE);
        }
    }

    /// `map`'s sectors as they are now: the live table, or the cartridge's where the map has
    /// no movers or light effects.
    pub fn sectors_of<'s>(&'s self, map: &MapTables<'s>) -> &'s [Sector] {
        match self.live {
            0 => map.sectors,
            live => &self.sectors[..live],
        }
    }

    /// `map` as it is now: its tables with the live sector and trigger tables in place of the
    /// cartridge's (the same tables where the map has no movers).
    pub fn map<'s>(&'s self, map: &MapTables<'s>) -> MapTables<'s> {
        if self.live == 0 {
            return *map;
        }
        MapTables {
            sectors: self.sectors_of(map),
            triggers: &self.triggers[..self.trigger_count],
            ..*map
        }
    }

    /// Puts each of `map`'s movers at the height `heights` gives it (in the order of
    /// `MapTables::movers`), for drawing a frame a log line describes.
    pub fn set_heights(&mut self, map: &MapTables, heights: &[i32]) {
        for (index, (mover, &height)) in map.movers.iter().zip(heights).enumerate() {
            self.movers[index].height = height;
            self.set_height(mover, height);
        }
    }

    /// Sets the light of the map's glowing, strobing and flickering sectors for a frame drawn
    /// at game tick `tick` (switched lights keep theirs). Run before drawing each frame: the
    /// levels are a function of the tick alone.
    pub fn show(&mut self, map: &MapTables, tick: u32) {
        if self.live == 0 {
            return;
        }
        for light in map.lights {
            if light.kind != LIGHT_SWITCHED {
                let high = map.sectors[usize::from(light.sector)].light;
                self.sectors[usize::from(light.sector)].light = level(light, high, tick);
            }
        }
    }

    /// Sets each light effect's sector to the level `levels` gives it (in the order of
    /// `MapTables::lights`), for drawing a frame a log line describes.
    pub fn set_lights(&mut self, map: &MapTables, levels: &[u8]) {
        for (light, &level) in map.lights.iter().zip(levels) {
            self.sectors[usize::from(light.sector)].light = level;
        }
    }

    /// The live level of each light effect's sector, in the order of `MapTables::lights`.
    pub fn lights<'s>(&'s self, map: &'s MapTables) -> impl Iterator<Item = u8> + Clone + 's {
        map.lights
            .iter()
            .map(move |light| self.sectors[usize::from(light.sector)].light)
    }

    /// Whether the map has movers or light effects: the world keeps its live tables.
    pub fn is_live(&self) -> bool {
        self.live != 0
    }

    /// Throws the map's switches that `thrown` says (one per trigger, in the order of
    /// `MapTables::triggers`), for drawing a frame a log line describes.
    pub fn set_thrown(&mut self, thrown: &[bool]) {
        for (trigger, &thrown) in self.triggers[..self.trigger_count].iter_mut().zip(thrown) {
            trigger.thrown = if thrown { TRIGGER_THROWN } else { 0 };
        }
    }

    /// The live state of the map's triggers (its switches thrown or not), in the order of
    /// `MapTables::triggers`.
    pub fn triggers(&self) -> &[Trigger] {
        &self.triggers[..self.trigger_count]
    }

    /// The live state of the map's movers, in the order of `MapTables::movers`.
    pub fn movers(&self) -> &[MoverState] {
        &self.movers[..self.mover_count]
    }

    fn set_height(&mut self, mover: &Mover, height: i32) {
        let sector = &mut self.sectors[usize::from(mover.sector)];
        if moves_floor(mover) {
            sector.floor_z = height;
        } else {
            sector.ceil_z = height;
        }
    }

    /// One game tick on a map with movers, the player's `intent` included: what the player
    /// starts starts, the movers move (turning back rather than closing on the player), then the
    /// player moves on the moved map, and the lines it crossed start their tags. Not inlined:
    /// in the game's tick its frame would sit on the stack on maps without movers too. In VRAM
    /// on the GBA (IWRAM has no room): it runs every tick.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".vram.world_tick_with_player")]
    pub fn tick_with_player(&mut self, map: &MapTables, player: &mut Player, intent: &Intent) {
        if intent.activate {
            self.use_button(map, player);
        }
        self.touch(map, player);
        self.tick(map, player);
        let before = player.sector;
        // The cartridge's walls among the live sectors: no copy of the map's tables.
        player.tick_among(intent, map, self.sectors_of(map));
        if player.sector != before {
            self.crossed(map, before, player.sector);
        }
    }

    /// One tick: every mover moves a step (or waits), unless the step would close on `player`,
    /// in which case it turns back. `map` is the cartridge's tables.
    pub fn tick(&mut self, map: &MapTables, player: &Player) {
        let mut from = 0;
        while let Some(index) = MoverState::next_moving(&self.movers[..self.mover_count], from) {
            self.advance(map, index, player);
            from = index + 1;
        }
        if self.thrown > 0 {
            self.release_switches(map);
        }
    }

    /// A thrown switch whose movers are all back at rest returns to its texture (and may be
    /// used again to the same effect); one of a platform or crusher, which never rests, stays
    /// thrown.
    #[inline(never)]
    fn release_switches(&mut self, map: &MapTables) {
        for index in 0..self.trigger_count {
            let trigger = self.triggers[index];
            if trigger.thrown == TRIGGER_THROWN
                && map
                    .movers
                    .iter()
                    .zip(&self.movers)
                    .all(|(mover, state)| mover.tag != trigger.tag || state.phase == Phase::Resting)
            {
                self.triggers[index].thrown = 0;
                self.thrown -= 1;
            }
        }
    }

    /// Not inlined: most ticks no mover moves, and inlined into [`World::tick`]'s loop its
    /// set-up (the map's tables loaded before the loop) would cost every tick.
    #[inline(never)]
    fn advance(&mut self, map: &MapTables, index: usize, player: &Player) {
        let mover = &map.movers[index];
        let state = self.movers[index];
        let (target, arriving) = match state.phase {
            Phase::Resting => return,
            Phase::WaitingAway | Phase::WaitingHome => {
                let state = &mut self.movers[index];
                if state.timer > 0 {
                    state.timer -= 1;
                } else {
                    state.phase = match state.phase {
                        Phase::WaitingAway => Phase::Back,
                        _ => Phase::Away,
                    };
                }
                return;
            }
            Phase::Away => (away_height(mover), Phase::WaitingAway),
            Phase::Back => (
                mover.start,
                if runs_always(mover) {
                    Phase::WaitingHome
                } else {
                    Phase::Resting
                },
            ),
        };
        let speed = i32::from(mover.speed.max(1));
        let height = if target > state.height {
            (state.height + speed).min(target)
        } else {
            (state.height - speed).max(target)
        };
        if !self.allows(map, mover, height, player) {
            self.movers[index].phase = match state.phase {
                Phase::Away => Phase::Back,
                _ => Phase::Away,
            };
            return;
        }
        self.set_height(mover, height);
        let state = &mut self.movers[index];
        state.height = height;
        if height == target {
            state.phase = arriving;
            state.timer = mover.wait;
        }
    }

    /// Whether `mover`'s plane may move to `height` with `player` where it is: a ceiling may
    /// always rise (it only makes room: a door opens even on a body already overlapping its
    /// doorway); else the body, as the move leaves it, still fits the moved sector if its disc
    /// touches it, and every other sector its disc touches if the move carries it.
    fn allows(&self, map: &MapTables, mover: &Mover, height: i32, player: &Player) -> bool {
        let index = mover.sector;
        if !moves_floor(mover) && height >= self.sectors[usize::from(index)].ceil_z {
            return true;
        }
        // The walls and vertices are the cartridge's; only heights live.
        if !touches(
            map,
            &map.sectors[usize::from(index)],
            player.position,
            RADIUS,
        ) {
            return true;
        }
        let live = self.map(map);
        let sector = &live.sectors[usize::from(index)];
        let mut moved = *sector;
        if moves_floor(mover) {
            moved.floor_z = height;
        } else {
            moved.ceil_z = height;
        }
        let mut body = player.body(live.sectors);
        let at = (player.position.x.to_bits(), player.position.y.to_bits());
        let carried = moves_floor(mover)
            && player.sector == index
            && !player.fly
            && (player.on_ground || body.feet.to_bits() < height * 256);
        if carried {
            body.feet = Fx24_8::from_int(height);
        }
        if !body.admits(live.slopes, &moved, at) {
            return false;
        }
        if !carried {
            return true;
        }
        // Carried: the sectors beyond the moved one's portals that the disc touches must still
        // take the body at its new height.
        live.sector_walls(sector)
            .iter()
            .all(|wall| match wall.neighbour() {
                Some(next) => {
                    let beyond = &live.sectors[usize::from(next)];
                    !touches(&live, beyond, player.position, RADIUS)
                        || body.admits(live.slopes, beyond, at)
                }
                None => true,
            })
    }

    /// The player pressed use: the mover in front of the eye within [`USE_RANGE`] (a door or a
    /// lift that opens on use, seen through its portal or stood in), or the switch there, starts.
    #[inline(never)]
    pub fn use_button(&mut self, map: &MapTables, player: &Player) {
        match self.use_target(map, player) {
            Some(UseTarget::Mover(index)) => self.start_mover(map, index, true),
            Some(UseTarget::Switch(index)) => {
                let trigger = &mut self.triggers[index];
                if trigger.thrown != TRIGGER_THROWN {
                    trigger.thrown = TRIGGER_THROWN;
                    self.thrown += 1;
                }
                let tag = trigger.tag;
                self.start_tag(map, tag);
            }
            None => {}
        }
    }

    fn use_target(&self, map: &MapTables, player: &Player) -> Option<UseTarget> {
        let live = self.map(map);
        let (sin, cos) = player.angle.sin_cos();
        let from = player.position;
        // The reach's end: USE_RANGE units along the view, 16.16 direction by 24.8 units.
        let reach = |unit: i32| ((i64::from(unit) * i64::from(USE_RANGE * 256)) >> 16) as i32;
        let to = WorldPoint::new(
            Fx24_8::from_bits(from.x.to_bits() + reach(cos.to_bits())),
            Fx24_8::from_bits(from.y.to_bits() + reach(sin.to_bits())),
        );
        let mut sector = player.sector;
        // A few portals at most lie within the reach.
        for _ in 0..4 {
            let here = self.mover_index(map, sector);
            let Some(wall_index) = exit_wall(&live, sector, from, to) else {
                // The reach ends inside this sector.
                return here
                    .filter(|&i| opens_on_use(&map.movers[i]))
                    .map(UseTarget::Mover);
            };
            let wall = &live.walls[wall_index];
            match wall.neighbour() {
                None => {
                    if let Some(index) = map
                        .triggers
                        .iter()
                        .position(|t| usize::from(t.wall) == wall_index && t.kind == TRIGGER_SWITCH)
                    {
                        return Some(UseTarget::Switch(index));
                    }
                    return here
                        .filter(|&i| opens_on_use(&map.movers[i]))
                        .map(UseTarget::Mover);
                }
                Some(next) => {
                    if let Some(index) = self
                        .mover_index(map, next)
                        .filter(|&i| opens_on_use(&map.movers[i]))
                    {
                        return Some(UseTarget::Mover(index));
                    }
                    if let Some(index) = here.filter(|&i| opens_on_use(&map.movers[i])) {
                        return Some(UseTarget::Mover(index));
                    }
                    sector = next;
                }
            }
        }
        None
    }

    /// A door that opens on touch within [`TOUCH_REACH`] of the body opens. Only a door through
    /// a portal of the player's sector can be that near (the body is smaller than a sector); it
    /// is looked for when the player's sector changes, as this runs every tick.
    pub fn touch(&mut self, map: &MapTables, player: &Player) {
        if player.sector != self.touch_sector {
            self.look_for_touch_door(player.sector);
        }
        let index = usize::from(self.touch_door);
        if self.touch_door == NONE || self.movers[index].phase != Phase::Resting {
            return;
        }
        let [min_x, min_y, max_x, max_y] = self.touch_box;
        let (x, y) = (
            player.position.x.to_int_floor(),
            player.position.y.to_int_floor(),
        );
        if x < min_x || x > max_x || y < min_y || y > max_y {
            return;
        }
        self.touch_near(map, player);
    }

    /// [`World::touch_door`] and its box for the player in `sector`, from the tables
    /// [`World::restart`] made. Not inlined: it runs only when the player's sector changes.
    #[inline(never)]
    fn look_for_touch_door(&mut self, sector: u16) {
        self.touch_sector = sector;
        self.touch_door = self.touch_doors[..self.live]
            .get(usize::from(sector))
            .copied()
            .unwrap_or(NONE);
        if let Some(touch_box) =
            self.touch_boxes[..self.mover_count].get(usize::from(self.touch_door))
        {
            self.touch_box = *touch_box;
        }
    }

    /// The exact test of [`World::touch`], for a body inside the touch door's box.
    #[inline(never)]
    fn touch_near(&mut self, map: &MapTables, player: &Player) {
        let index = usize::from(self.touch_door);
        let sector = &map.sectors[usize::from(map.movers[index].sector)];
        if touches(map, sector, player.position, RADIUS + TOUCH_REACH) {
            self.start_mover(map, index, false);
        }
    }

    /// The player's centre went from sector `from` to sector `to`: the walk-over lines of
    /// `from` facing `to` start their tags. Out of line: the player's sector changes on few
    /// ticks.
    #[inline(never)]
    pub fn crossed(&mut self, map: &MapTables, from: u16, to: u16) {
        let Some(sector) = map.sectors.get(usize::from(from)) else {
            return;
        };
        let walls =
            usize::from(sector.first_wall)..usize::from(sector.first_wall + sector.wall_count);
        for trigger in map.triggers {
            if trigger.kind == TRIGGER_LINE
                && walls.contains(&usize::from(trigger.wall))
                && map.walls[usize::from(trigger.wall)].portal == to
            {
                self.start_tag(map, trigger.tag);
            }
        }
    }

    /// Mover `index` starts as the use button starts it (an open door closes).
    pub fn use_mover(&mut self, map: &MapTables, index: usize) {
        self.start_mover(map, index, true);
    }

    /// Every mover tagged `tag` starts, and every light switched by `tag` turns low if it is
    /// high, high if it is not.
    pub fn start_tag(&mut self, map: &MapTables, tag: u16) {
        if tag == 0 {
            return;
        }
        for index in 0..map.movers.len() {
            if map.movers[index].tag == tag {
                self.start_mover(map, index, false);
            }
        }
        for light in map.lights {
            if light.kind == LIGHT_SWITCHED && light.tag == tag {
                let high = map.sectors[usize::from(light.sector)].light;
                let sector = &mut self.sectors[usize::from(light.sector)];
                sector.light = if sector.light == high {
                    light.low
                } else {
                    high
                };
            }
        }
    }

    /// Starts mover `index`: a resting or closing door opens (an open one closes, by use), a
    /// resting lift goes down. Platforms and crushers run anyway.
    fn start_mover(&mut self, map: &MapTables, index: usize, by_use: bool) {
        let mover = &map.movers[index];
        let state = &mut self.movers[index];
        state.phase = match (mover.kind, state.phase) {
            (MOVER_DOOR, Phase::Resting | Phase::Back) => Phase::Away,
            (MOVER_DOOR, Phase::WaitingAway) if by_use => Phase::Back,
            (MOVER_LIFT, Phase::Resting) => Phase::Away,
            (_, phase) => phase,
        };
    }

    /// The index in `MapTables::movers` of `sector`'s mover, if it moves.
    pub fn mover_index(&self, map: &MapTables, sector: u16) -> Option<usize> {
        mover_of(map, sector)
    }
}

/// The level of `light`'s sector (its high level `high`) at game tick `tick`; a switched
/// light's high level, as it starts.
pub fn level(light: &Light, high: u8, tick: u32) -> u8 {
    let period = u32::from(light.period.max(2));
    let at = tick % period;
    match light.kind {
        LIGHT_GLOW => {
            // A triangle: down from high to low over the first half, back up over the second.
            let half = period / 2;
            let from_high = at.min(period - at).min(half);
            let drop = u32::from(high.saturating_sub(light.low)) * from_high / half;
            high - drop as u8
        }
        LIGHT_STROBE if at < u32::from(STROBE_FLASH_TICKS) => high,
        LIGHT_STROBE => light.low,
        LIGHT_FLICKER if flicker_draw(light.sector, tick / period).is_multiple_of(4) => light.low,
        _ => high,
    }
}

/// A well-mixed 32-bit number from a sector and a flicker's slot: the same on every run, and
/// unlike for neighbouring slots and sectors (the finaliser of MurmurHash3).
fn flicker_draw(sector: u16, slot: u32) -> u32 {
    let mut x = slot ^ u32::from(sector).wrapping_mul(0x9e37_79b9);
    x ^= x >> 16;
    x = x.wrapping_mul(0x85eb_ca6b);
    x ^= x >> 13;
    x = x.wrapping_mul(0xc2b2_ae35);
    x ^ (x >> 16)
}

/// What the use button reaches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum UseTarget {
    /// A mover, by index in `MapTables::movers`.
    Mover(usize),
    /// A switch, by index in `MapTables::triggers`.
    Switch(usize),
}

fn opens_on_use(mover: &Mover) -> bool {
    mover.flags & MOVER_ON_USE != 0 && matches!(mover.kind, MOVER_DOOR | MOVER_LIFT)
}

/// Whether a disc of radius `radius` (world units) centred at `p` may touch `sector`: `p` lies
/// less than `radius` outside every wall's line. Near a corner this takes in a little more than
/// the disc (a mover turns back a little early there, never late).
fn touches(map: &MapTables, sector: &Sector, p: WorldPoint, radius: i32) -> bool {
    map.sector_walls(sector).iter().all(|wall| {
        let (a, b) = wall_points(map, wall);
        // The wall's length in 24.8 bits, by the radius in 24.8 bits: the cross product's scale.
        cross(a, b, p) > -(i64::from(radius * 256) * i64::from(wall.length_fx8))
    })
}

/// Whether a player's body centred at `p` in sector `sector` lies in that sector alone: its
/// disc touches none of the sectors beyond its portals (by the test a mover's rules use, so they
/// would see it only there).
pub fn body_only_in(map: &MapTables, sector: u16, p: WorldPoint) -> bool {
    map.sector_walls(&map.sectors[usize::from(sector)])
        .iter()
        .filter_map(|wall| wall.neighbour())
        .all(|next| !touches(map, &map.sectors[usize::from(next)], p, RADIUS))
}

/// The bounding box of `sector`'s vertices grown by the body's radius and [`TOUCH_REACH`] (and
/// a unit to spare): a centre whose floored coordinates lie outside it is too far.
fn reach_box(map: &MapTables, sector: &Sector) -> TouchBox {
    let reach = RADIUS + TOUCH_REACH + 1;
    map.sector_walls(sector).iter().fold(
        [i32::MAX, i32::MAX, i32::MIN, i32::MIN],
        |[min_x, min_y, max_x, max_y], wall| {
            let v = map.vertices[usize::from(wall.start)];
            [
                min_x.min(v.x - reach),
                min_y.min(v.y - reach),
                max_x.max(v.x + reach),
                max_y.max(v.y + reach),
            ]
        },
    )
}

/// The wall of `sector` through which the segment `from → to` leaves it, if it does.
fn exit_wall(map: &MapTables, sector: u16, from: WorldPoint, to: WorldPoint) -> Option<usize> {
    let record = map.sectors.get(usize::from(sector))?;
    let first = usize::from(record.first_wall);
    map.sector_walls(record)
        .iter()
        .enumerate()
        .find(|(_, wall)| {
            let (a, b) = wall_points(map, wall);
            // From the inside of the wall's line to the outside, between its ends.
            cross(a, b, from) > 0
                && cross(a, b, to) <= 0
                && (cross(from, to, a) >= 0) != (cross(from, to, b) >= 0)
        })
        .map(|(offset, _)| first + offset)
}

/// Takes thing `index` off a game's own copy of a map's things (`things`, with its
/// `sector_things` index; on the GBA, copies in EWRAM: `hw::memory::ewram_copy`): a pickup
/// taken, a monster gone. The thing moves behind the last sector's range, where no sector's
/// walk or collision finds it, and the things after it move up one place, so every sector's
/// things keep their order (its solid ones first). Draw and move with
/// `MapTables { things, sector_things, ..*map }`. Returns false, changing nothing, if `index`
/// is not a thing the index holds (taken already, or out of range).
///
/// ```
/// # use portalcast::world::remove_thing;
/// # use portalcast_format::Thing;
/// let thing = |x_fx8| Thing { x_fx8, y_fx8: 0, angle: 0, sprite: 0, sector: 0, z: 0, radius: 8, flags: 0, frame_ticks: 1 };
/// // Two sectors: sector 0 holds things 0 and 1, sector 1 holds thing 2.
/// let (mut things, mut sector_things) = ([thing(0), thing(256), thing(512)], [0u16, 2, 3]);
/// assert!(remove_thing(&mut things, &mut sector_things, 0));
/// assert_eq!(sector_things, [0, 1, 2]);
/// assert_eq!((things[0].x_fx8, things[1].x_fx8), (256, 512));
/// assert!(!remove_thing(&mut things, &mut sector_things, 2));
/// ```
pub fn remove_thing(things: &mut [Thing], sector_things: &mut [u16], index: usize) -> bool {
    let Some(&held) = sector_things.last() else {
        return false;
    };
    if index >= usize::from(held) || index >= things.len() {
        return false;
    }
    things[index..usize::from(held)].rotate_left(1);
    for start in sector_things.iter_mut() {
        if usize::from(*start) > index {
            *start -= 1;
        }
    }
    true
}
