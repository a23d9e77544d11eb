//! Map tables: vertices, walls, sectors, the player start and things.

/// [`Wall::portal`] of a solid wall.
pub const NO_PORTAL: u16 = u16::MAX;
/// A texture slot that is never drawn (the middle of a portal; an upper or lower strip that
/// the heights make invisible).
pub const NO_TEXTURE: u16 = u16::MAX;
/// [`Sector::ceil_texture`] of a sector open to the sky: draw the sky panorama instead.
pub const SKY: u16 = u16::MAX - 1;

/// A map vertex, in integer world units (1 unit = 1 texel at mip level 0).
///
/// The compiler guarantees `|x|, |y| <= limits::WORLD_COORD_MAX` and that no two vertices of a
/// map share a position, so vertex indices identify points (a renderer may cache per-vertex
/// transforms by index).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct Vertex {
    /// World x.
    pub x: i32,
    /// World y (drawn downward on a top-down view).
    pub y: i32,
}

/// One side of a sector's boundary, from vertex `start` to vertex `end`.
///
/// Stored clockwise (top-down view, y down): the sector's inside is to the right of
/// `start → end`. A sector's walls are consecutive in [`MapTables::walls`], and wall `i`'s `end`
/// is wall `i + 1`'s `start` (wrapping to the sector's first wall).
///
/// Texture coordinates: `u` is the distance along the wall from `start`, plus `x_offset`; `v`
/// grows downward, plus `y_offset`. Both are in texels of mip level 0 and wrap at the texture's
/// size. Where `v = 0` sits vertically (top of the strip, or a world height) is the renderer's
/// choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct Wall {
    /// Index of the start vertex in [`MapTables::vertices`].
    pub start: u16,
    /// Index of the end vertex (the next wall's start).
    pub end: u16,
    /// Index of the sector on the other side, or [`NO_PORTAL`] for a solid wall. The neighbour
    /// has a wall `end → start` whose portal is this wall's sector.
    pub portal: u16,
    /// Texture of a solid wall, index into the textures table; [`NO_TEXTURE`] on a portal.
    pub texture: u16,
    /// Portal only: the strip between the neighbour's ceiling and this sector's (lower) ceiling.
    /// [`NO_TEXTURE`] where the neighbour's ceiling is not lower, or both sectors show the sky.
    pub upper_texture: u16,
    /// Portal only: the strip between this sector's floor and the neighbour's (higher) floor.
    /// [`NO_TEXTURE`] where the neighbour's floor is not higher.
    pub lower_texture: u16,
    /// Horizontal texture offset, in texels.
    pub x_offset: i16,
    /// Vertical texture offset, in texels.
    pub y_offset: i16,
    /// The wall's length in 24.8 world units, `floor(256·√(Δx² + Δy²))`: computed by the map
    /// compiler, so the renderer takes no square root per wall.
    pub length_fx8: i32,
    /// Portal only: a colour-keyed image drawn in the opening (grates, bars, railings, a window
    /// frame), index into the sprite sets table (a still image); [`NO_TEXTURE`] for none. Its
    /// top is at the opening's top (the lower of the two ceilings) plus `y_offset`, its column
    /// `floor(u) mod width`; it does not repeat vertically.
    pub middle: u16,
    /// [`WALL_MIDDLE_BLOCKS`], [`WALL_MIDDLE_TRANSLUCENT`], [`WALL_SWITCH`].
    pub flags: u16,
}

/// [`Wall::flags`]: the player cannot pass the portal (its middle image is a barrier).
pub const WALL_MIDDLE_BLOCKS: u16 = 1;
/// [`Wall::flags`]: the middle image is drawn at 50 % over what is behind it.
pub const WALL_MIDDLE_TRANSLUCENT: u16 = 2;
/// [`Wall::flags`]: a solid wall that is a switch (a [`TRIGGER_SWITCH`] trigger's wall): while
/// the switch is thrown it shows the trigger's `used_texture` ([`MapTables::solid_texture`]).
pub const WALL_SWITCH: u16 = 4;
/// [`Thing::flags`]: the sprite is drawn at 50 % over what is behind it.
pub const THING_TRANSLUCENT: u16 = 4;

impl Wall {
    /// The sector on the other side, or `None` for a solid wall.
    pub const fn neighbour(&self) -> Option<u16> {
        if self.portal == NO_PORTAL {
            None
        } else {
            Some(self.portal)
        }
    }
}

/// A convex region of the map with a floor and a ceiling, each flat or sloped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct Sector {
    /// Index of the sector's first wall in [`MapTables::walls`].
    pub first_wall: u16,
    /// Number of walls (at least 3). Consecutive walls may be collinear (a wall split where a
    /// neighbour's portal starts), never of zero length.
    pub wall_count: u16,
    /// Floor height, world units; `floor_z < ceil_z`. A sloped floor's lowest height at the
    /// sector's vertices, rounded down: the anchor of its lower strips' textures.
    pub floor_z: i32,
    /// Ceiling height, world units. A sloped ceiling's highest height at the sector's vertices,
    /// rounded up: the anchor of its walls' and upper strips' textures.
    pub ceil_z: i32,
    /// Floor texture, index into the textures table (its row-major flat copy is present).
    pub floor_texture: u16,
    /// Ceiling texture (its flat copy is present), or [`SKY`].
    pub ceil_texture: u16,
    /// Light level: 0 is black, [`LIGHT_NEUTRAL`](crate::LIGHT_NEUTRAL) (128) shows textures
    /// as painted, 255 brightens them about twice. Select the colormap row with
    /// [`colormap_row`](crate::colormap_row).
    pub light: u8,
    /// [`LINK_CEILING`] and [`LINK_FLOOR`]: which of the sector's ceiling and floor are
    /// portals to a sector of another layer (room over room), found in
    /// [`MapTables::layer_links`]. 0 for most sectors.
    pub links: u8,
    /// Index in [`MapTables::slopes`] of the sector's planes where its floor or ceiling is
    /// sloped, else [`NO_SLOPE`]. The compiler keeps one entry per distinct pair of planes, so
    /// two sectors have the same planes exactly when their indices are equal.
    pub slope: u16,
}

/// [`Sector::slope`] of a sector whose floor and ceiling are both flat.
pub const NO_SLOPE: u16 = u16::MAX;

/// [`Sector::links`]: the ceiling is a portal to the sector above ([`LayerLink::above`]).
pub const LINK_CEILING: u8 = 1;
/// [`Sector::links`]: the floor is a portal to the sector below ([`LayerLink::below`]).
pub const LINK_FLOOR: u8 = 2;
/// [`LayerLink::above`] or [`LayerLink::below`] where that plane is solid.
pub const NO_LINK: u16 = u16::MAX;

/// Room over room: the sectors a sector's ceiling and floor open into. Linked sectors have the
/// same outline (the same corners, on different layers) and meet at one flat height: the lower
/// one's ceiling is the upper one's floor. A ray or a body crossing that height passes from one
/// to the other; the plane itself is never drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(C)]
pub struct LayerLink {
    /// The sector whose floor is this one's ceiling, or [`NO_LINK`].
    pub above: u16,
    /// The sector whose ceiling is this one's floor, or [`NO_LINK`].
    pub below: u16,
}

/// A plane of heights over the map: `z(x, y) = base + gradient_x·x + gradient_y·y`, the height
/// at world point `(x, y)`. A flat floor or ceiling is the plane with both gradients 0.
///
/// The map compiler derives it from a map's heights at three or more vertices and stores it in
/// fixed point: `base` in 24.8, the gradients in 8.24 (at most
/// [`SLOPE_GRADIENT_MAX`](crate::limits::SLOPE_GRADIENT_MAX) units of rise per unit of run, so
/// they fit with room for their products). Each is rounded to nearest, so within the map's
/// limits ([`WORLD_COORD_MAX`](crate::limits::WORLD_COORD_MAX)) [`Plane::height_fx8_at`] is
/// within [`PLANE_ERROR_BOUND_FX8`] (24.8 bits, under 1/100 unit) of the exact plane through
/// the map's heights.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(C)]
pub struct Plane {
    /// The height at the world origin, 24.8.
    pub base_fx8: i32,
    /// Rise per unit along +x, 8.24.
    pub gradient_x_fx24: i32,
    /// Rise per unit along +y, 8.24.
    pub gradient_y_fx24: i32,
}

/// Largest difference, in 24.8 bits, between [`Plane::height_fx8_at`] and the exact plane
/// through the map's heights, anywhere within the map's limits: the base's rounding (½ bit),
/// each gradient's (2^-25 per unit of distance from the origin, at most 2^13 + 2^13 units of
/// it over both axes: 1/8 bit) and the result's (½ bit), rounded up.
pub const PLANE_ERROR_BOUND_FX8: i32 = 2;

impl Plane {
    /// The flat plane at height `z` (world units).
    pub const fn flat(z: i32) -> Plane {
        Plane {
            base_fx8: z * 256,
            gradient_x_fx24: 0,
            gradient_y_fx24: 0,
        }
    }

    /// Whether both gradients are 0.
    pub const fn is_flat(&self) -> bool {
        self.gradient_x_fx24 == 0 && self.gradient_y_fx24 == 0
    }

    /// The height at world point `(x_fx8, y_fx8)` (24.8), in 24.8, rounded to nearest (ties
    /// up). Within the limits the products stay below 2^50 and the result within i32.
    #[inline]
    pub fn height_fx8_at(&self, x_fx8: i32, y_fx8: i32) -> i32 {
        let rise = i64::from(self.gradient_x_fx24) * i64::from(x_fx8)
            + i64::from(self.gradient_y_fx24) * i64::from(y_fx8);
        self.base_fx8 + ((rise + (1 << 23)) >> 24) as i32
    }
}

/// [`MapTables::heights_fx8_at`] with the map's [`MapTables::slopes`] alone, for code that
/// holds the slopes and a (live) sector but not the map.
#[inline]
pub fn sector_heights_fx8_at(
    slopes: &[SectorSlope],
    sector: &Sector,
    x_fx8: i32,
    y_fx8: i32,
) -> (i32, i32) {
    match slopes.get(usize::from(sector.slope)) {
        None => (sector.floor_z * 256, sector.ceil_z * 256),
        Some(slope) => (
            slope.floor.height_fx8_at(x_fx8, y_fx8),
            slope.ceiling.height_fx8_at(x_fx8, y_fx8),
        ),
    }
}

/// The floor and ceiling planes of a sector with a sloped floor or ceiling
/// ([`Sector::slope`]); the flat one of the two is [`Plane::flat`] at its height.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(C)]
pub struct SectorSlope {
    /// The floor.
    pub floor: Plane,
    /// The ceiling.
    pub ceiling: Plane,
}

/// Where and how the player enters the map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct PlayerStart {
    /// World x in 24.8 fixed point (`x_fx8 / 256.0` units).
    pub x_fx8: i32,
    /// World y in 24.8 fixed point.
    pub y_fx8: i32,
    /// View direction, binary angle: 65536 per turn, 0 along +x, growing toward +y.
    pub angle: u16,
    /// The sector that strictly contains the start position (never on a wall line).
    pub sector: u16,
    /// The player's body on this map.
    pub size: PlayerSize,
}

/// The player's body as a map's format has it: heights in world units. The radius is the
/// engine's one 16 (Doom's too), which the collision code's bounds are proved for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct PlayerSize {
    /// Eye height above the feet, standing.
    pub eye_height: i32,
    /// Body height: the eye keeps `height − eye_height` below any ceiling.
    pub height: i32,
    /// The highest floor step the player climbs without jumping (and steps down without
    /// falling).
    pub step_up: i32,
}

impl PlayerSize {
    /// portalcast's own maps: eye 32, height 48, steps of 16 (the thesis' proportions).
    pub const NATIVE: PlayerSize = PlayerSize {
        eye_height: 32,
        height: 48,
        step_up: 16,
    };
    /// Doom's player: eye 41, height 56, steps of 24.
    pub const DOOM: PlayerSize = PlayerSize {
        eye_height: 41,
        height: 56,
        step_up: 24,
    };
    /// Lowest standing eye a map may give: the crouched eye's 16 (a player stands at least as
    /// tall as it crouches).
    pub const EYE_HEIGHT_MIN: i32 = 16;
    /// Highest standing eye a map may give.
    pub const EYE_HEIGHT_MAX: i32 = 128;
    /// Highest step a map may give: four times the radius. Beyond it a step would be a wall.
    pub const STEP_UP_MAX: i32 = 64;

    /// Room the eye keeps below a ceiling.
    pub const fn headroom(&self) -> i32 {
        self.height - self.eye_height
    }
}

/// A named object placed on the map, drawn as a sprite that faces the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct Thing {
    /// World x in 24.8 fixed point.
    pub x_fx8: i32,
    /// World y in 24.8 fixed point.
    pub y_fx8: i32,
    /// Facing, binary angle as [`PlayerStart::angle`].
    pub angle: u16,
    /// Index into the sprite sets table (`SpriteSet`: its images, animation frames and
    /// rotations).
    pub sprite: u16,
    /// The sector that strictly contains the thing.
    pub sector: u16,
    /// Height of the sprite's bottom above its sector's floor, in world units; with
    /// [`THING_HANGING`], of the sprite's top below the ceiling.
    pub z: i16,
    /// Radius of the thing's footprint, in world units: at least half the sprite's width (the
    /// compiler keeps the footprint inside the sector, so the sprite never pokes through a wall).
    pub radius: u16,
    /// [`THING_HANGING`], [`THING_SOLID`].
    pub flags: u16,
    /// Game ticks (60 a second) each animation frame of its sprite set shows; at least 1.
    pub frame_ticks: u16,
}

/// [`Thing::flags`]: the sprite hangs from the ceiling ([`Thing::z`] below it) instead of
/// standing on the floor.
pub const THING_HANGING: u16 = 1;
/// [`Thing::flags`]: the player cannot walk into the thing's footprint.
pub const THING_SOLID: u16 = 2;

/// A sector whose floor or ceiling moves while the game runs: a door, a lift, a platform or a
/// crusher. The map's [`Sector`] record holds the heights the map maker drew; the game keeps
/// the live ones (`portalcast::world`), starting from [`Mover::start`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct Mover {
    /// The sector that moves.
    pub sector: u16,
    /// [`MOVER_DOOR`], [`MOVER_LIFT`], [`MOVER_PLATFORM`] or [`MOVER_CRUSHER`].
    pub kind: u8,
    /// [`MOVER_ON_USE`], [`MOVER_ON_TOUCH`].
    pub flags: u8,
    /// The lower of the moving plane's two heights, world units: a door's or a crusher's
    /// ceiling when closed, a lift's or a platform's floor when lowered.
    pub low: i32,
    /// The higher: a door's or a crusher's open ceiling (the sector's `ceil_z`), a lift's
    /// raised floor (the sector's `floor_z`), a platform's other end.
    pub high: i32,
    /// World units the plane moves per tick (60 ticks a second), at least 1.
    pub speed: u16,
    /// Ticks the mover waits at its far end before it goes back.
    pub wait: u16,
    /// Switches and walk-over lines with this tag ([`Trigger::tag`]) start it; 0: none do.
    pub tag: u16,
    /// The height the plane has when the map starts: `low` for a door (closed) and a platform,
    /// `high` for a lift (raised) and a crusher (open).
    pub start: i32,
}

/// [`Mover::kind`]: the ceiling goes up from `low` (the floor) to `high`, waits, and comes down;
/// it goes back up if it would come down on the player.
pub const MOVER_DOOR: u8 = 0;
/// [`Mover::kind`]: the floor goes down from `high` to `low`, waits, and comes back up, carrying
/// the player; it goes back down if the player's head would meet the ceiling.
pub const MOVER_LIFT: u8 = 1;
/// [`Mover::kind`]: the floor moves between `low` and `high` without end, waiting `wait` ticks
/// at each.
pub const MOVER_PLATFORM: u8 = 2;
/// [`Mover::kind`]: the ceiling moves between `high` and `low` without end, waiting `wait` ticks
/// at each; it goes back up if it would come down on the player.
pub const MOVER_CRUSHER: u8 = 3;
/// [`Mover::flags`]: the player starts it with the use button, facing one of its portals.
pub const MOVER_ON_USE: u8 = 1;
/// [`Mover::flags`]: the player starts it by walking into one of its portals.
pub const MOVER_ON_TOUCH: u8 = 2;

/// A sector whose light level changes while the game runs: it glows, strobes or flickers by
/// itself, or a switch or a walk-over line turns it down and up. The map's [`Sector::light`] is
/// the high level; the game keeps the live one (`portalcast::world`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct Light {
    /// The sector whose light changes.
    pub sector: u16,
    /// [`LIGHT_GLOW`], [`LIGHT_STROBE`], [`LIGHT_FLICKER`] or [`LIGHT_SWITCHED`].
    pub kind: u8,
    /// The low level, below the sector's [`Sector::light`] (the high one).
    pub low: u8,
    /// Ticks (60 a second) of one cycle: a glow's fall and rise, a strobe's flash and dark, a
    /// flicker's time at one level before it draws again. At least 2 (a strobe's: more than
    /// [`STROBE_FLASH_TICKS`]). Unused by a switched light.
    pub period: u16,
    /// A switched light: the switches and walk-over lines with this tag ([`Trigger::tag`])
    /// turn it down, and up again. 0 for the others.
    pub tag: u16,
}

/// [`Light::kind`]: the level falls from high to low and rises back, evenly, each `period`.
pub const LIGHT_GLOW: u8 = 0;
/// [`Light::kind`]: the level is high for [`STROBE_FLASH_TICKS`] of each `period`, low for the
/// rest.
pub const LIGHT_STROBE: u8 = 1;
/// [`Light::kind`]: for each `period` ticks, high or (one time in four, at random but the same
/// on every run) low.
pub const LIGHT_FLICKER: u8 = 2;
/// [`Light::kind`]: high until a trigger of its tag turns it low, then high at the next one.
pub const LIGHT_SWITCHED: u8 = 3;
/// Ticks a strobe's flash lasts.
pub const STROBE_FLASH_TICKS: u16 = 5;

/// A wall that starts the movers of its tag: a switch the player uses (its texture changes)
/// or a portal line the player walks over.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct Trigger {
    /// The wall, index in [`MapTables::walls`].
    pub wall: u16,
    /// The movers it starts ([`Mover::tag`]).
    pub tag: u16,
    /// [`TRIGGER_SWITCH`] or [`TRIGGER_LINE`].
    pub kind: u8,
    /// A switch is thrown ([`TRIGGER_THROWN`]) or not (0). Always 0 in a map's tables; a
    /// game's live copy of them sets it while the switch shows its `used_texture`.
    pub thrown: u8,
    /// A switch's texture once used (index into the textures table); [`NO_TEXTURE`] for a
    /// line.
    pub used_texture: u16,
}

/// [`Trigger::kind`]: a solid wall the player uses, facing it.
pub const TRIGGER_SWITCH: u8 = 0;
/// [`Trigger::kind`]: a portal wall the player crosses, from its side.
pub const TRIGGER_LINE: u8 = 1;
/// [`Trigger::thrown`]: the switch is thrown.
pub const TRIGGER_THROWN: u8 = 1;

/// Everything the engine needs to run one map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct MapTables<'a> {
    /// The map's file name without extension (`bench` for `maps/bench.map`).
    pub name: &'a str,
    /// All vertices; walls refer to them by index.
    pub vertices: &'a [Vertex],
    /// All walls, grouped by sector (see [`Sector::first_wall`]).
    pub walls: &'a [Wall],
    /// All sectors; sector ids (portals, player start) are indices into this table.
    pub sectors: &'a [Sector],
    /// The player's start.
    pub player_start: PlayerStart,
    /// Placed objects, grouped by sector in sector order, each sector's solid ones
    /// ([`THING_SOLID`]) first.
    pub things: &'a [Thing],
    /// Where each sector's things start in [`MapTables::things`], and one past the last: one
    /// entry more than there are sectors, or none when the map has no things.
    pub sector_things: &'a [u16],
    /// The sectors that move, at most one mover a sector, in sector order.
    pub movers: &'a [Mover],
    /// Switches and walk-over lines, in wall order.
    pub triggers: &'a [Trigger],
    /// The sectors whose light changes, at most one effect a sector, in sector order.
    pub lights: &'a [Light],
    /// For each wall, the index of the same wall seen from its portal's sector (its twin:
    /// the first wall of that sector whose portal leads back and whose ends are this one's,
    /// swapped), or [`NO_TWIN`]: the map compiler's [`find_twin`] of every wall, so that a
    /// body crossing a portal need not search the next sector's walls. Empty in tables built
    /// by hand: [`MapTables::twin`] then searches.
    pub wall_twins: &'a [u16],
    /// The planes of the sectors with a sloped floor or ceiling ([`Sector::slope`]), each
    /// distinct pair once.
    pub slopes: &'a [SectorSlope],
    /// Room over room: each sector's [`LayerLink`], indexed by sector, or empty when no sector
    /// has a floor or ceiling portal ([`Sector::links`]).
    pub layer_links: &'a [LayerLink],
}

/// [`MapTables::wall_twins`] of a solid wall, or of a portal whose sector has no twin for it.
pub const NO_TWIN: u16 = u16::MAX;

/// The twin of wall `index` of `walls` (see [`MapTables::wall_twins`]), whose sector is
/// `sector`: searched among the walls of its portal's sector.
pub fn find_twin(walls: &[Wall], sectors: &[Sector], sector: u16, index: usize) -> Option<usize> {
    let wall = walls.get(index)?;
    let next = wall.neighbour()?;
    let there = sectors.get(usize::from(next))?;
    let first = usize::from(there.first_wall);
    (first..first + usize::from(there.wall_count)).find(|&at| {
        walls.get(at).is_some_and(|other| {
            other.portal == sector && other.start == wall.end && other.end == wall.start
        })
    })
}

impl<'a> MapTables<'a> {
    /// The texture solid wall `wall` (index `index` in [`MapTables::walls`]) shows now: a
    /// thrown switch's `used_texture`, else [`Wall::texture`]. Only a [`WALL_SWITCH`] wall
    /// looks further than its flags.
    #[inline]
    pub fn solid_texture(&self, index: u16, wall: &Wall) -> u16 {
        if wall.flags & WALL_SWITCH == 0 {
            return wall.texture;
        }
        match self
            .triggers
            .binary_search_by_key(&index, |trigger| trigger.wall)
        {
            Ok(at) if self.triggers[at].thrown == TRIGGER_THROWN => self.triggers[at].used_texture,
            _ => wall.texture,
        }
    }

    /// The twin of wall `index`, of sector `sector` ([`MapTables::wall_twins`]): from the
    /// compiler's table, or searched where the tables have none.
    #[inline]
    pub fn twin(&self, sector: u16, index: usize) -> Option<usize> {
        if self.wall_twins.is_empty() {
            return find_twin(self.walls, self.sectors, sector, index);
        }
        match self.wall_twins.get(index) {
            Some(&NO_TWIN) | None => None,
            Some(&twin) => Some(usize::from(twin)),
        }
    }

    /// The floor and ceiling planes of `sector`: its [`SectorSlope`], or flat planes at its
    /// heights.
    #[inline]
    pub fn planes(&self, sector: &Sector) -> SectorSlope {
        match self.slopes.get(usize::from(sector.slope)) {
            Some(slope) => *slope,
            None => SectorSlope {
                floor: Plane::flat(sector.floor_z),
                ceiling: Plane::flat(sector.ceil_z),
            },
        }
    }

    /// The floor and ceiling heights of `sector` at world point `(x_fx8, y_fx8)`, 24.8: its
    /// heights where both are flat, its planes' ([`Plane::height_fx8_at`]) where one slopes.
    /// `sector` may be a live copy whose heights moved: a sector that moves is never sloped.
    #[inline]
    pub fn heights_fx8_at(&self, sector: &Sector, x_fx8: i32, y_fx8: i32) -> (i32, i32) {
        sector_heights_fx8_at(self.slopes, sector, x_fx8, y_fx8)
    }

    /// The sector above sector `index`, into which its ceiling opens ([`LayerLink::above`]).
    #[inline]
    pub fn sector_above(&self, index: u16) -> Option<u16> {
        match self.layer_links.get(usize::from(index)) {
            Some(link) if link.above != NO_LINK => Some(link.above),
            _ => None,
        }
    }

    /// The sector below sector `index`, into which its floor opens ([`LayerLink::below`]).
    #[inline]
    pub fn sector_below(&self, index: u16) -> Option<u16> {
        match self.layer_links.get(usize::from(index)) {
            Some(link) if link.below != NO_LINK => Some(link.below),
            _ => None,
        }
    }

    /// The sector of the stack through sector `index` (linked by floor and ceiling portals)
    /// that holds height `z_fx8` (24.8): up through open ceilings while `z` is at or above the
    /// ceiling, down through open floors while it is below the floor. A height at a link
    /// belongs to the sector above it. Out of line: the engine asks it of each body it stands
    /// somewhere, and inlined its loop took stack in every caller's frame.
    #[inline(never)]
    pub fn sector_at_height(&self, mut index: u16, z_fx8: i32) -> u16 {
        if self.layer_links.is_empty() {
            return index;
        }
        // Each step goes strictly up or strictly down a stack of distinct heights: it ends.
        loop {
            let sector = &self.sectors[usize::from(index)];
            match (self.sector_above(index), self.sector_below(index)) {
                (Some(above), _) if z_fx8 >= sector.ceil_z * 256 => index = above,
                (_, Some(below)) if z_fx8 < sector.floor_z * 256 => index = below,
                _ => return index,
            }
        }
    }

    /// The walls of `sector`, in clockwise order.
    #[inline]
    pub fn sector_walls(&self, sector: &Sector) -> &'a [Wall] {
        let first = sector.first_wall as usize;
        &self.walls[first..first + sector.wall_count as usize]
    }

    /// The indices in [`MapTables::things`] of the things standing in sector `sector_index`.
    #[inline]
    pub fn things_range(&self, sector_index: u16) -> core::ops::Range<usize> {
        let index = usize::from(sector_index);
        match (
            self.sector_things.get(index),
            self.sector_things.get(index + 1),
        ) {
            (Some(&first), Some(&end)) => usize::from(first)..usize::from(end),
            _ => 0..0,
        }
    }

    /// The things standing in sector `sector_index`.
    #[inline]
    pub fn things_in(&self, sector_index: u16) -> &'a [Thing] {
        &self.things[self.things_range(sector_index)]
    }
}
