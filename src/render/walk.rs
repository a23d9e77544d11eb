//! The sector walk (Doom's r_bsp): front to back from the eye's sector, through portals, with a
//! clip window per column. Each visit of a sector draws the walls and strips of the columns it
//! was given, records its ceiling and floor windows, draws those planes, and then goes on into
//! its portals with the narrowed windows. Columns handed to different portals never overlap, so
//! one set of per-column arrays serves the whole walk. The walk is depth first, with its levels
//! in the renderer's memory rather than on the call stack (`Renderer::walk`): no function calls
//! itself.

use portalcast_format::{
    MapTables, Sector, Texture, Wall, LINK_CEILING, LINK_FLOOR, NO_PORTAL, NO_SLOPE, NO_TEXTURE,
    SKY,
};

use super::planes;
use super::spans::Window;
use super::surface::Surface;
use super::things::{PortalSeen, ThingView, Things};
use super::view::{Preprocessing, ThingsShown, View};
use super::visits::{VisitId, VisitPlan};
use super::walls::{
    owned_columns_in, SlopedHeights, SteppedWall, VertexSplit, WallProjector, WallRows,
    WallStepper, ROW_HEIGHTS,
};
use super::RenderAssets;
use crate::math::{recip_small, EyePoint, Fx24_8, Fx2_30, WorldPoint};
use crate::raster::column::ColumnTexture;
use crate::raster::wall_run::{
    RunTexturing, StripRunLevel, WallKind, WallRun, WallRunEnd, CEILING_SEEN, FLOOR_SEEN,
};
use crate::raster::Canvas;
use crate::render::light::{light_row, run_light, Lighting};
use core::cell::Cell;
use core::convert::Infallible;

/// Widest screen, in columns.
pub const MAX_COLUMNS: usize = 240;
/// Tallest screen, in rows.
pub const MAX_ROWS: usize = 160;
/// Deepest chain of portals followed; deeper sectors are left undrawn and counted.
pub const MAX_PORTAL_DEPTH: u32 = 256;

/// Portals the walk keeps on record at once ([`Renderer::portals`]): those owning columns of
/// the visits on its current path. A path that finds more has its visits' portals tested again.
const PORTALS_RECORDED: usize = 256;

/// Portals into a neighbour with the same planes ([`same_planes`]) a visit's wall pass may
/// leave open at once for the visit to draw the neighbour's walls as its own
/// ([`Renderer::see_through`]); more are drawn as plain portals.
const SEE_THROUGH_MAX: usize = 16;

/// Plane windows the walk keeps at once for the floor and ceiling portals it has yet to enter
/// ([`Renderer::layer_windows`]): a sector's portals to other layers are entered once its own
/// portals' walks are done, so one waits while the sectors in front of it are drawn. Four
/// full-width planes; a fifth waiting at once is counted in [`LayerCounts::overflows`]
/// and its plane drawn as solid.
const LAYER_WINDOWS: usize = 4 * MAX_COLUMNS;

/// A waiting plane window's rows, each in a byte (rows are below [`MAX_ROWS`] = 160): half
/// the EWRAM of a [`Window`], which the textures' share of EWRAM keeps.
type SavedWindow = [u8; 2];

/// Floor and ceiling portals waiting at once ([`Renderer::layers`]).
const LAYERS_WAITING: usize = 8;

/// A floor or ceiling portal a visit found showing rows, waiting for the visit's other
/// portals to be walked: the sector beyond, the columns, where its windows are kept, and the
/// walk level of the visit that found it.
#[derive(Clone, Copy)]
struct WaitingLayer {
    sector: u16,
    first: i16,
    end: i16,
    windows_from: u16,
    depth: u16,
}

/// What the wall pass did with a portal ([`Renderer::note_portal`]).
enum PortalNoted {
    /// It sees through it into a neighbour with the same planes: nothing of it is drawn.
    SeenThrough,
    /// It recorded it for the walk.
    Recorded,
    /// The record is full: the walk tests the visit's portals again.
    RecordFull,
}

/// A portal a visit's wall pass found owning columns `start..stop`, and the sector behind it.
#[derive(Clone, Copy)]
struct OwnedPortal {
    sector: u16,
    start: i16,
    stop: i16,
}

/// Counters of one frame, for the benchmarks and the tests.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Sector visits (a sector seen through two portals counts twice).
    pub sector_visits: u32,
    /// Wall columns evaluated (solid and portal).
    pub wall_columns: u32,
    /// Pixels drawn by column kernels (walls, strips, sky).
    pub column_pixels: u32,
    /// Pixels drawn by span kernels (floors, ceilings).
    pub span_pixels: u32,
    /// Wall strips drawn (column kernel calls of the wall stage).
    pub strips: u32,
    /// Of [`FrameStats::column_pixels`], the sky's (drawn in the plane stage).
    pub sky_pixels: u32,
    /// Floor and ceiling spans drawn (span kernel calls).
    pub spans: u32,
    /// Portal chains cut at [`MAX_PORTAL_DEPTH`].
    pub depth_cutoffs: u32,
    /// Draws of a sector already drawn this frame (seen through another portal): what the
    /// scene preprocessing ([`Preprocessing::On`]) merges where their columns touch. Counted
    /// for sectors below [`VISITS_TRACKED`].
    pub repeat_visits: u32,
    /// Visits the thesis' scene preprocessing merged into another visit of the same sector
    /// (each saves a draw): `sector_visits` counts the draws.
    pub merged_visits: u32,
    /// Frames whose visits overflowed the preprocessing's plan and were drawn by the plain
    /// walk (0 or 1 per frame).
    pub plan_overflows: u32,
    /// Clock ticks in the wall stage (ownership, projection, wall and strip columns), when the
    /// renderer has a clock (the ROM's cycle meter); 0 otherwise.
    pub wall_ticks: u32,
    /// Clock ticks in the plane stage (spans, floors, ceilings, sky).
    pub plane_ticks: u32,
    /// Things drawn (once per visit they were seen in).
    pub things_drawn: u32,
    /// Things seen but left out for want of room ([`super::things::VISIBLE_THINGS_MAX`],
    /// [`super::things::THING_CLIP_COLUMNS`]).
    pub things_dropped: u32,
    /// Clock ticks in the things stage's drawing (its collection counts in the wall stage).
    pub thing_ticks: u32,
    /// Portal middles drawn (once per visit of their sector).
    pub middles_drawn: u32,
    /// Of the things and middles drawn, the translucent ones.
    pub translucent_drawn: u32,
}

/// Room over room's counters of the last frame drawn ([`Renderer::layer_counts`]): kept in the
/// renderer's memory, not in [`FrameStats`], which lives on the GBA's stack while a frame is
/// drawn and has no room left to grow.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LayerCounts {
    /// Visits through a floor or ceiling portal into another layer.
    pub visits: u32,
    /// Floor or ceiling portals left undrawn for want of room (the renderer keeps the windows
    /// of four full-width planes waiting, eight portals): their plane is drawn as solid.
    pub overflows: u32,
}

/// The renderer's per-column and per-row working memory: the clip and plane windows every wall
/// column reads and writes, the span starts `make_spans` keeps, the sky's column angles. It is
/// touched at every column and every span, so the ROM keeps it where a halfword costs one
/// cycle (`hw::memory::VramWindows`). All zeros is the empty state.
#[repr(C, align(4))]
pub struct ColumnWindows {
    clip: [Window; MAX_COLUMNS],
    ceiling: [Window; MAX_COLUMNS],
    floor: [Window; MAX_COLUMNS],
    span_start: [i16; MAX_ROWS],
    column_angles: [i16; MAX_COLUMNS],
}

impl ColumnWindows {
    /// Empty windows (all zeros).
    pub const fn new() -> ColumnWindows {
        ColumnWindows {
            clip: [Window::EMPTY; MAX_COLUMNS],
            ceiling: [Window::EMPTY; MAX_COLUMNS],
            floor: [Window::EMPTY; MAX_COLUMNS],
            span_start: [0; MAX_ROWS],
            column_angles: [0; MAX_COLUMNS],
        }
    }

    /// The clip windows, one per column: what a [`WindowStore`] opens each frame.
    pub(crate) fn clip_mut(&mut self) -> &mut [Window] {
        &mut self.clip
    }
}

impl Default for ColumnWindows {
    fn default() -> Self {
        ColumnWindows::new()
    }
}

/// Where a [`Renderer`] keeps its [`ColumnWindows`]: in itself on the host, at a fixed address
/// in fast memory on the GBA.
pub trait WindowStore {
    /// The windows.
    fn windows(&mut self) -> &mut ColumnWindows;

    /// Opens the clip windows of columns `0..width` to rows `0..height`, as every frame starts
    /// (the eye's sector is seen through the whole screen).
    fn open_clip(&mut self, width: usize, height: i16) {
        for window in &mut self.windows().clip_mut()[..width] {
            *window = Window {
                top: 0,
                bottom: height,
            };
        }
    }
}

impl WindowStore for ColumnWindows {
    #[inline(always)]
    fn windows(&mut self) -> &mut ColumnWindows {
        self
    }
}

/// The renderer's per-frame working memory: the column windows (in `W`), the portal walk's
/// levels, the visit plan and the vertex cache.
pub struct Renderer<W: WindowStore = ColumnWindows> {
    windows: W,
    /// The viewport width [`ColumnWindows::column_angles`] were computed for.
    column_angles_width: i32,
    clock: fn() -> u32,
    visited: [u32; VISITS_TRACKED / 32],
    /// The portal walk's levels: level `d` is the sector visited at depth `d` (see
    /// [`Renderer::walk`]).
    levels: [WalkLevel; MAX_PORTAL_DEPTH as usize + 1],
    /// The portals each visit on the walk's path found owning columns (a stack: a visit's
    /// entries sit above its parent's), so that the walk enters them without testing their
    /// ownership a second time.
    portals: [OwnedPortal; PORTALS_RECORDED],
    /// Entries of [`Renderer::portals`] in use.
    portals_used: u16,
    /// The portals the visit being drawn sees through into a neighbour with the same planes,
    /// not yet drawn (Doom's `R_AddLine` skips such a line: nothing of it shows): the visit
    /// draws each neighbour's walls in the portal's columns as if they were its own, with the
    /// clip windows it has there, and its floor and ceiling cover the neighbour's as one plane.
    /// No wall column of the portal is evaluated, and a row across several such sectors is one
    /// span.
    see_through: [OwnedPortal; SEE_THROUGH_MAX],
    /// Entries of [`Renderer::see_through`] waiting.
    see_through_used: u16,
    /// The walls of the waiting neighbours: each may record a portal, so the record keeps room
    /// for them.
    see_through_walls: u16,
    /// Whether the wall pass records its portals: only while the walk draws a visit.
    recording_portals: bool,
    /// Whether the last visit drawn recorded all of its portals.
    portals_recorded: bool,
    /// Whether the walk leaves out a sector whose portal shows no row (every clip window of its
    /// columns closed): only while it draws, when the windows are those the walls left.
    skip_closed: bool,
    /// Which of the visit's plane windows its walls wrote with rows in them (`CEILING_SEEN`,
    /// `FLOOR_SEEN`): a plane with none is not drawn (about half of a frame's planes).
    planes_seen: u32,
    /// The scene preprocessing's visits ([`Preprocessing::On`]).
    plan: VisitPlan,
    /// Each vertex's eye-space position (and the precision knob's column) this frame.
    vertices: VertexCache,
    /// The frame's number in [`Renderer::vertices`]: an entry with another is stale.
    frame_stamp: u32,
    /// The things the visits saw, for drawing after the scene.
    things: Things,
    /// The sectors (by index, a bit each, below [`VISITS_TRACKED`]) with a portal that has a
    /// middle image, for the map whose walls start at [`Renderer::middles_of`].
    middle_sectors: [u32; VISITS_TRACKED / 32],
    middles_of: usize,
    /// Whether the map may have a middle image: [`Renderer::middle_sectors`] marks a sector, or
    /// some sectors are past the tracked ones.
    any_middles: bool,
    /// The plane windows of the floor and ceiling portals waiting in [`Renderer::layers`], a
    /// stack: each visit's above those of the visits on the walk's path before it.
    layer_windows: [SavedWindow; LAYER_WINDOWS],
    /// Floor and ceiling portals found, not yet entered (a stack, as the walk's levels).
    layers: [WaitingLayer; LAYERS_WAITING],
    /// Entries of [`Renderer::layers`] in use.
    layers_used: u16,
    /// The walk level of the visit being drawn, for the floor and ceiling portals it finds.
    walk_depth: u16,
    /// The frame's floor and ceiling portal counts.
    layer_counts: LayerCounts,
}

/// Vertices (by index) whose eye-space position a frame keeps once computed; higher ones are
/// transformed at every use.
pub const VERTICES_CACHED: usize = 2048;

/// A vertex's eye-space position this frame, and its first column in front of the eye
/// ([`NO_COLUMN`] behind it, where each visit's split is found by bisection).
#[derive(Clone, Copy)]
struct CachedVertex {
    stamp: u32,
    point: EyePoint,
    first_column: i32,
}

/// [`CachedVertex::first_column`] of a vertex at or behind the eye.
const NO_COLUMN: i32 = i32::MIN;

/// The per-frame vertex cache: every visit of a sector (the portal walk's and the drawing's)
/// asks for its walls' vertices, and neighbouring sectors share them, so each is transformed
/// and placed among the columns once a frame instead of at every use. Cells,
/// so that the walk can fill it through the shared borrows it holds.
struct VertexCache([Cell<CachedVertex>; VERTICES_CACHED]);

/// One level of the portal walk: the sector visited, the next of its walls to look at, and the
/// ownership state of its walls so far (each vertex is projected once per visit).
#[derive(Clone, Copy)]
struct WalkLevel {
    sector: u16,
    next_wall: u16,
    ownership: Ownership,
    /// The visit in the preprocessing's plan (its first pass only).
    visit: Option<VisitId>,
    /// The portals the visit's wall pass found owning columns, in wall order: the next one's
    /// index in [`Renderer::portals`] and one past its last. `None` where the wall pass did not
    /// record them (the preprocessing's first pass draws nothing; or the record was full):
    /// [`WalkLevel::next_portal`] then tests each portal's ownership again.
    recorded: Option<(u16, u16)>,
    /// [`Renderer::portals_used`] before the visit recorded its portals: where the record is cut
    /// back to when the visit is done.
    records_from: u16,
}

impl WalkLevel {
    const fn new(sector: u16, first: i32, end: i32) -> WalkLevel {
        WalkLevel {
            sector,
            next_wall: 0,
            ownership: Ownership::new(first, end),
            visit: None,
            recorded: None,
            records_from: 0,
        }
    }

    /// The next of the sector's portals that owns some of the level's columns: the sector
    /// behind it and those columns. Moves past it, so the next call finds the one after.
    #[inline(always)]
    fn next_portal(
        &mut self,
        scene: &Scene,
        vertices: &VertexCache,
        portals: &[OwnedPortal],
    ) -> Option<(u16, i32, i32)> {
        if let Some((next, end)) = self.recorded {
            let portal = portals[usize::from(next)..usize::from(end)].first()?;
            self.recorded = Some((next + 1, end));
            return Some((portal.sector, portal.start.into(), portal.stop.into()));
        }
        self.next_portal_tested(scene, vertices)
    }

    /// [`WalkLevel::next_portal`] without a record: tests the ownership of each of the
    /// sector's portals. Out of line and from ROM (no IWRAM section attribute): only the
    /// preprocessing's first pass and a full record take it.
    #[inline(never)]
    fn next_portal_tested(
        &mut self,
        scene: &Scene,
        vertices: &VertexCache,
    ) -> Option<(u16, i32, i32)> {
        let walls = scene
            .map
            .sector_walls(&scene.map.sectors[usize::from(self.sector)]);
        while let Some(wall) = walls.get(usize::from(self.next_wall)) {
            self.next_wall += 1;
            if wall.portal == NO_PORTAL {
                continue;
            }
            if let Some((_, _, start, stop)) = self.ownership.wall(scene, vertices, wall) {
                return Some((wall.portal, start, stop));
            }
        }
        None
    }
}

/// A plane window no wall column has set yet (debug builds only).
const UNSET: Window = Window {
    top: i16::MIN,
    bottom: i16::MIN,
};

/// Sectors (by index) a frame tracks for [`FrameStats::repeat_visits`] (a bit each) and the
/// scene preprocessing merges (higher ones are never merged).
pub const VISITS_TRACKED: usize = 2048;

fn no_clock() -> u32 {
    0
}

impl Default for Renderer<ColumnWindows> {
    fn default() -> Self {
        Renderer::new()
    }
}

/// What a visit needs that does not change during the frame.
struct Scene<'s, 'a> {
    map: &'s MapTables<'a>,
    assets: &'s RenderAssets<'a>,
    view: &'s View,
    /// The 2.30 reciprocal of `d_y` (its bits), for the wall columns' `z'/d_y`.
    inverse_focal_y: i64,
    /// [`Renderer::frame_stamp`].
    frame_stamp: u32,
    /// What the things stage needs of the frame.
    things: ThingView<'s, 'a>,
    /// Whether the map has floor or ceiling portals ([`MapTables::layer_links`]): asked once a
    /// frame, so that a visit on another map reads no sector's links.
    layered: bool,
}

impl VertexCache {
    /// Vertex `index`'s eye-space position and its first column ([`NO_COLUMN`] where the split
    /// takes a bisection): from the cache if this frame computed them already.
    #[inline]
    fn get(&self, scene: &Scene, index: u16) -> (EyePoint, i32) {
        let entry = self.0.get(usize::from(index));
        if let Some(entry) = entry {
            let cached = entry.get();
            if cached.stamp == scene.frame_stamp {
                return (cached.point, cached.first_column);
            }
        }
        let exact = scene.view.eye.to_eye_exact(vertex(scene.map, index));
        let point = exact.rounded();
        let viewport = &scene.view.viewport;
        // In front of the eye the exact split of any range is the vertex's first column,
        // clamped into it (`VertexSplit::from_first_column`): found once a frame over the
        // whole width instead of over each visit's columns, on the unrounded point, so that the
        // column's ray decides, not the rounding (`ExactEyePoint`).
        let first_column = if point.z.to_bits() > 0 {
            viewport.first_column_at_or_after_exact(exact)
        } else {
            NO_COLUMN
        };
        if let Some(entry) = entry {
            entry.set(CachedVertex {
                stamp: scene.frame_stamp,
                point,
                first_column,
            });
        }
        (point, first_column)
    }
}

impl Renderer<ColumnWindows> {
    /// A renderer with empty working memory.
    pub const fn new() -> Renderer<ColumnWindows> {
        Renderer::with_windows(ColumnWindows::new())
    }
}

impl<W: WindowStore> Renderer<W> {
    /// Times the wall and plane stages with `clock` (a free-running counter, e.g. the ROM's
    /// cycle meter), reported in [`FrameStats`].
    pub fn set_clock(&mut self, clock: fn() -> u32) {
        self.clock = clock;
    }

    /// A renderer with empty working memory, its column windows in `windows` (which must hold
    /// empty windows).
    pub const fn with_windows(windows: W) -> Renderer<W> {
        Renderer {
            windows,
            column_angles_width: 0,
            visited: [0; VISITS_TRACKED / 32],
            clock: no_clock,
            levels: [WalkLevel::new(0, 0, 0); MAX_PORTAL_DEPTH as usize + 1],
            portals: [OwnedPortal {
                sector: 0,
                start: 0,
                stop: 0,
            }; PORTALS_RECORDED],
            portals_used: 0,
            see_through: [OwnedPortal {
                sector: 0,
                start: 0,
                stop: 0,
            }; SEE_THROUGH_MAX],
            see_through_used: 0,
            see_through_walls: 0,
            recording_portals: false,
            skip_closed: false,
            planes_seen: 0,
            portals_recorded: false,
            plan: VisitPlan::new(),
            vertices: VertexCache(
                [const {
                    Cell::new(CachedVertex {
                        stamp: 0,
                        point: EyePoint::new(Fx24_8::ZERO, Fx24_8::ZERO),
                        first_column: NO_COLUMN,
                    })
                }; VERTICES_CACHED],
            ),
            frame_stamp: 0,
            things: Things::new(),
            middle_sectors: [0; VISITS_TRACKED / 32],
            middles_of: 0,
            any_middles: false,
            layer_windows: [[0; 2]; LAYER_WINDOWS],
            layers: [WaitingLayer {
                sector: 0,
                first: 0,
                end: 0,
                windows_from: 0,
                depth: 0,
            }; LAYERS_WAITING],
            layers_used: 0,
            walk_depth: 0,
            layer_counts: LayerCounts {
                visits: 0,
                overflows: 0,
            },
        }
    }

    /// Draws the frame `view` sees of `map` onto `canvas`.
    pub fn render(
        &mut self,
        map: &MapTables,
        assets: &RenderAssets,
        view: &View,
        canvas: &mut impl Canvas,
    ) -> FrameStats {
        let width = view.viewport.width as usize;
        let height = view.viewport.height as i16;
        debug_assert_eq!(width, canvas.resolution().width());
        canvas.prefer_lighting(view.lighting != Lighting::Off);
        // The counters live on the stack (IWRAM on the GBA), not in the renderer's memory
        // (EWRAM): the wall columns and strips count into them.
        let mut stats = FrameStats::default();
        // Only the words of the map's sectors: a fill of the whole table from ROM cost about
        // 1,000 cycles a frame.
        let visited_words = map.sectors.len().div_ceil(32).min(self.visited.len());
        self.visited[..visited_words].fill(0);
        self.frame_stamp = self.frame_stamp.wrapping_add(1);
        if self.frame_stamp == 0 {
            self.forget_vertices();
        }
        if self.column_angles_width != view.viewport.width {
            self.fill_column_angles(&view.viewport);
        }
        self.windows.open_clip(width, height);
        let scene = Scene {
            map,
            assets,
            view,
            inverse_focal_y: i64::from(recip_small(view.viewport.focal_y as u32).to_bits()),
            frame_stamp: self.frame_stamp,
            things: ThingView::new(map, assets, view),
            layered: !map.layer_links.is_empty(),
        };
        self.things.clear();
        if self.middles_of != map.walls.as_ptr() as usize {
            self.find_middle_sectors(map);
        }
        let planned = view.preprocessing == Preprocessing::On
            && self.plan_visits(&scene, &mut stats, view.sector, 0, width as i32);
        if planned {
            self.draw_plan(&scene, canvas, &mut stats);
        } else {
            self.walk(&scene, canvas, &mut stats, view.sector, 0, width as i32);
        }
        if !map.things.is_empty() || self.any_middles {
            let things_started = (self.clock)();
            let things = self.things.draw(assets, canvas);
            stats.things_drawn = things.drawn;
            stats.things_dropped = things.dropped;
            stats.middles_drawn = things.middles;
            stats.translucent_drawn = things.translucent;
            stats.thing_ticks = (self.clock)().wrapping_sub(things_started);
        }
        stats
    }

    /// Room over room's counts of the last frame [`Renderer::render`] drew.
    pub fn layer_counts(&self) -> LayerCounts {
        self.layer_counts
    }

    /// The column angles of `viewport`'s columns, for the sky: computed when the resolution
    /// changes, so from ROM (no IWRAM section attribute).
    #[inline(never)]
    fn fill_column_angles(&mut self, viewport: &crate::math::Viewport) {
        let width = viewport.width as usize;
        column_angles(
            viewport.centre_x(),
            viewport.focal_x,
            &mut self.windows.windows().column_angles[..width],
        );
        self.column_angles_width = viewport.width;
    }

    /// Marks the sectors of `map` with a portal that has a middle image. Once per map, from ROM.
    #[inline(never)]
    fn find_middle_sectors(&mut self, map: &MapTables) {
        self.middle_sectors = [0; VISITS_TRACKED / 32];
        for (index, sector) in map.sectors.iter().enumerate().take(VISITS_TRACKED) {
            if map
                .sector_walls(sector)
                .iter()
                .any(|wall| wall.middle != NO_TEXTURE)
            {
                self.middle_sectors[index / 32] |= 1 << (index % 32);
            }
        }
        self.middles_of = map.walls.as_ptr() as usize;
        // Sectors past the tracked ones are looked at one by one ([`Renderer::has_middles`]).
        self.any_middles =
            self.middle_sectors.iter().any(|&word| word != 0) || map.sectors.len() > VISITS_TRACKED;
    }

    /// Whether sector `index` may have a portal with a middle image (sectors past
    /// [`VISITS_TRACKED`] are looked at).
    #[inline(always)]
    fn has_middles(&self, index: u16) -> bool {
        self.middle_sectors
            .get(usize::from(index) / 32)
            .is_none_or(|word| word & (1 << (index % 32)) != 0)
    }

    /// Collects the middle images of the portals of sector `sector_index` that own columns of
    /// the visit `first..end`, just drawn: the clip windows now hold the openings. From ROM:
    /// only sectors with middles come here.
    #[inline(never)]
    fn collect_middles(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        visit: u16,
        sector_index: u16,
        first: i32,
        end: i32,
    ) {
        let sector = &scene.map.sectors[usize::from(sector_index)];
        let first_wall = sector.first_wall;
        for (offset, wall) in scene.map.sector_walls(sector).iter().enumerate() {
            if wall.middle == NO_TEXTURE || wall.portal == NO_PORTAL {
                continue;
            }
            let mut ownership = Ownership::new(first, end);
            let Some((a, b, start, stop)) = ownership.wall(scene, &self.vertices, wall) else {
                continue;
            };
            let seen = PortalSeen {
                visit,
                sector: sector_index,
                wall: first_wall + offset as u16,
                ends: (a, b),
                columns: start..stop,
            };
            self.things
                .collect_middle(&scene.things, seen, &self.windows.windows().clip, canvas);
        }
    }

    /// After 2^32 frames the vertex cache's stamps come round: every entry is forgotten. From
    /// ROM, like [`Renderer::fill_column_angles`].
    #[inline(never)]
    fn forget_vertices(&mut self) {
        for entry in &self.vertices.0 {
            entry.set(CachedVertex {
                stamp: 0,
                ..entry.get()
            });
        }
        self.frame_stamp = 1;
    }

    /// The scene preprocessing's first pass: the walk of [`Renderer::walk`], in the same order,
    /// drawing nothing, recording each visit in [`Renderer::plan`]. False if the plan
    /// overflowed ([`crate::render::visits::MAX_VISITS`]).
    ///
    /// Run from ROM (no IWRAM section attribute), like
    /// [`Renderer::draw_plan`]: in IWRAM the two took 2.6 KB of the stack's room, which the
    /// kernel check scene's 4 KB texture on the stack needs.
    #[inline(never)]
    fn plan_visits(
        &mut self,
        scene: &Scene,
        stats: &mut FrameStats,
        sector_index: u16,
        first: i32,
        end: i32,
    ) -> bool {
        self.plan.clear();
        // The plan orders visits by the portals between sectors, not by floor and ceiling
        // portals: a map with them is drawn by the plain walk (not an overflow).
        if !scene.map.layer_links.is_empty() {
            return false;
        }
        let planned = self.walk_portals::<_, false>(
            scene,
            stats,
            sector_index,
            first,
            end,
            |renderer, stats, sector, first, end, parent| {
                let visit = renderer.plan.record(sector, first, end, parent);
                if visit.is_err() {
                    // The plain walk draws the frame and counts again.
                    stats.depth_cutoffs = 0;
                }
                visit.map(Some)
            },
        );
        stats.plan_overflows = u32::from(planned.is_err());
        planned.is_ok()
    }

    /// The scene preprocessing's second pass: each group of merged visits drawn once, every
    /// sector after the sectors in front of it.
    #[inline(never)]
    fn draw_plan(&mut self, scene: &Scene, canvas: &mut impl Canvas, stats: &mut FrameStats) {
        while let Some((sector_index, first, end)) = self.plan.next_draw() {
            self.draw_sector(scene, canvas, stats, sector_index, first, end);
        }
        stats.merged_visits = self.plan.visit_count() - stats.sector_visits;
    }

    /// The portal walk: draws `sector_index` in columns `first..end`, then, depth first and
    /// front to back, every sector seen through its portals, each in the columns its portal
    /// owns.
    ///
    /// The recursion's state is kept in [`Renderer::levels`] (the renderer's memory: EWRAM on
    /// the GBA), not on the call stack: a level is a sector and how far its portals have been
    /// followed. The GBA's stack (8 KB of IWRAM) then holds one drawing frame whatever the
    /// depth; recursing through calls cost ~300 bytes a level, so a chain of
    /// [`MAX_PORTAL_DEPTH`] portals overran it.
    ///
    /// Out of line, so that [`Renderer::render`]'s own set-up stays small enough to be inlined
    /// into its callers. In the cartridge, not IWRAM: its loop runs once a portal and a visit,
    /// and IWRAM's code left the stack no room over its reserve.
    #[inline(never)]
    fn walk(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        sector_index: u16,
        first: i32,
        end: i32,
    ) {
        self.skip_closed = true;
        let draw = |renderer: &mut Self, stats: &mut FrameStats, sector, first, end, _| {
            renderer.draw_sector(scene, canvas, stats, sector, first, end);
            Ok::<_, Infallible>(None)
        };
        // Two copies of the walk (ROM, where each instruction of a loop costs its fetch): the
        // one for maps with floor and ceiling portals keeps their checks out of the other's.
        let Ok(()) = if scene.layered {
            self.walk_portals::<_, true>(scene, stats, sector_index, first, end, draw)
        } else {
            self.walk_portals::<_, false>(scene, stats, sector_index, first, end, draw)
        };
        self.skip_closed = false;
    }

    /// Enters `level`'s visit (`enter`: draws it, or plans it) with the wall pass recording the
    /// portals it finds owning columns; notes the record in `level`.
    #[inline(always)]
    fn enter_recording<E>(
        &mut self,
        stats: &mut FrameStats,
        level: &mut WalkLevel,
        parent: Option<VisitId>,
        enter: &mut impl FnMut(
            &mut Self,
            &mut FrameStats,
            u16,
            i32,
            i32,
            Option<VisitId>,
        ) -> Result<Option<VisitId>, E>,
    ) -> Result<Option<VisitId>, E> {
        level.records_from = self.portals_used;
        self.recording_portals = true;
        self.portals_recorded = false;
        let visit = enter(
            self,
            stats,
            level.sector,
            level.ownership.first,
            level.ownership.end,
            parent,
        );
        self.recording_portals = false;
        level.recorded = self
            .portals_recorded
            .then_some((level.records_from, self.portals_used));
        visit
    }

    /// The portal walk's order, shared by the drawing walk and the preprocessing's plan:
    /// `enter` is called for `sector_index` in columns `first..end`, then, depth first and front
    /// to back, for every sector seen through its portals with the columns its portal owns and
    /// what `enter` returned for the sector in front. An error from `enter` ends the walk.
    /// `LAYERED`: the map has floor and ceiling portals ([`Scene::layered`]), whose waiting
    /// windows the walk enters once each visit's own portals are walked.
    #[inline(always)]
    fn walk_portals<E, const LAYERED: bool>(
        &mut self,
        scene: &Scene,
        stats: &mut FrameStats,
        sector_index: u16,
        first: i32,
        end: i32,
        mut enter: impl FnMut(
            &mut Self,
            &mut FrameStats,
            u16,
            i32,
            i32,
            Option<VisitId>,
        ) -> Result<Option<VisitId>, E>,
    ) -> Result<(), E> {
        self.portals_used = 0;
        self.layers_used = 0;
        self.walk_depth = 0;
        self.layer_counts = LayerCounts::default();
        let mut root = WalkLevel::new(sector_index, first, end);
        root.visit = self.enter_recording(stats, &mut root, None, &mut enter)?;
        self.levels[0] = root;
        let mut depth = 0;
        loop {
            // A copy in registers while its walls are tested; the levels live in EWRAM.
            let mut level = self.levels[depth];
            let mut seen = level.next_portal(scene, &self.vertices, &self.portals);
            self.levels[depth] = level;
            if LAYERED && seen.is_none() && self.layers_used != 0 {
                // The visit's own portals are walked: its floor and ceiling portals next.
                seen = self.next_waiting_layer(depth);
            }
            match seen {
                Some(_) if depth as u32 == MAX_PORTAL_DEPTH => stats.depth_cutoffs += 1,
                // A sector seen through no row of its portal draws nothing, nor does any
                // sector behind it (about a tenth of the bench map's visits): left out.
                Some((_, start, stop))
                    if self.skip_closed
                        && self.windows.windows().clip[start as usize..stop as usize]
                            .iter()
                            .all(|window| window.is_empty()) => {}
                Some((neighbour, start, stop)) => {
                    if LAYERED {
                        self.walk_depth = depth as u16 + 1;
                    }
                    let mut next = WalkLevel::new(neighbour, start, stop);
                    next.visit = self.enter_recording(stats, &mut next, level.visit, &mut enter)?;
                    depth += 1;
                    self.levels[depth] = next;
                }
                None if depth == 0 => return Ok(()),
                None => {
                    // The visit's records are done with: its parent's are on top again.
                    self.portals_used = level.records_from;
                    depth -= 1;
                }
            }
        }
    }

    /// The floor or ceiling portal the visit at walk level `depth` found and is the last to
    /// wait, if any: the sector beyond and its columns, whose clip windows are now the plane's
    /// windows the visit left there. Out of line and in ROM: only maps with floor and ceiling
    /// portals come here.
    #[inline(never)]
    fn next_waiting_layer(&mut self, depth: usize) -> Option<(u16, i32, i32)> {
        let top = *self.layers[..usize::from(self.layers_used)].last()?;
        if usize::from(top.depth) != depth {
            return None;
        }
        self.layers_used -= 1;
        let (first, end) = (usize::from(top.first as u16), usize::from(top.end as u16));
        let from = usize::from(top.windows_from);
        let saved = &self.layer_windows[from..from + (end - first)];
        for (clip, &[top, bottom]) in self.windows.windows().clip[first..end]
            .iter_mut()
            .zip(saved)
        {
            *clip = Window {
                top: top.into(),
                bottom: bottom.into(),
            };
        }
        self.layer_counts.visits += 1;
        Some((top.sector, first as i32, end as i32))
    }

    /// After the walls of a visit of `sector` (sector `sector_index`, columns `first..end`)
    /// with a floor or ceiling portal: the portal's plane is not drawn, and where the eye is on
    /// its open side and it shows rows, its windows wait for the walk to enter the sector
    /// beyond through them ([`Renderer::next_waiting_layer`]). Out of line and in ROM: only
    /// such sectors come here.
    #[inline(never)]
    fn open_layers(
        &mut self,
        scene: &Scene,
        (sector, sector_index): (&Sector, u16),
        first: i32,
        end: i32,
    ) {
        let eye_z = scene.view.eye_z.to_bits();
        let (first, end) = (first as usize, end as usize);
        // The floor's first, so the ceiling's is the one on top: entered first, as any order
        // would do (their rows never meet).
        let planes = [
            (
                LINK_FLOOR,
                FLOOR_SEEN,
                scene.map.sector_below(sector_index),
                eye_z >= sector.floor_z * 256,
            ),
            (
                LINK_CEILING,
                CEILING_SEEN,
                scene.map.sector_above(sector_index),
                eye_z < sector.ceil_z * 256,
            ),
        ];
        for (link, seen, beyond, eye_on_open_side) in planes {
            if sector.links & link == 0 {
                continue;
            }
            let shows_rows = self.planes_seen & seen != 0;
            // The portal's plane is never drawn: from the far side its rows are none.
            self.planes_seen &= !seen;
            let Some(beyond) = beyond.filter(|_| eye_on_open_side && shows_rows) else {
                continue;
            };
            let used = usize::from(self.layers_used);
            let from = match used.checked_sub(1) {
                Some(last) => {
                    let last = self.layers[last];
                    usize::from(last.windows_from) + usize::from((last.end - last.first) as u16)
                }
                None => 0,
            };
            let windows = if seen == CEILING_SEEN {
                &self.windows.windows().ceiling[first..end]
            } else {
                &self.windows.windows().floor[first..end]
            };
            if used == LAYERS_WAITING || from + windows.len() > LAYER_WINDOWS {
                self.layer_counts.overflows += 1;
                self.planes_seen |= seen;
                continue;
            }
            for (saved, window) in self.layer_windows[from..from + windows.len()]
                .iter_mut()
                .zip(windows)
            {
                // A window's rows are on the screen (0 ..= 160), an empty one's too.
                debug_assert!((0..=MAX_ROWS as i16).contains(&window.top.max(window.bottom)));
                debug_assert!(window.top.min(window.bottom) >= 0);
                *saved = [window.top as u8, window.bottom as u8];
            }
            self.layers[used] = WaitingLayer {
                sector: beyond,
                first: first as i16,
                end: end as i16,
                windows_from: from as u16,
                depth: self.walk_depth,
            };
            self.layers_used += 1;
        }
    }

    /// One visit of `sector_index` in columns `first..end`: its walls and strips, then its
    /// ceiling and floor, narrowing the clip windows of the columns its portals own. Out of
    /// line: [`Renderer::walk`] calls it for every sector it enters, and the preprocessing's
    /// [`Renderer::draw_plan`] for every group.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram_render.draw_sector")]
    fn draw_sector(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        sector_index: u16,
        first: i32,
        end: i32,
    ) {
        self.count_visit(stats, sector_index);
        let sector = &scene.map.sectors[usize::from(sector_index)];
        // Every column of `[first, end)` is owned by exactly one wall of the sector (the
        // ownership rule, module `walls`: around the sector's closed outline the vertices right
        // of a column's ray form one run, and the ray crosses the sector: the eye is inside the
        // first sector, and a portal's column has its two ends on either side), and its wall
        // column sets its ceiling and floor windows: no reset is needed. Debug builds (the host
        // tests) mark the windows unset and check that every one was set.
        let range = first as usize..end as usize;
        if cfg!(debug_assertions) {
            let windows = self.windows.windows();
            windows.ceiling[range.clone()].fill(UNSET);
            windows.floor[range.clone()].fill(UNSET);
        }
        self.planes_seen = 0;
        let walls_started = (self.clock)();
        // The sector's own walls, then those of the neighbours it sees through (each a visit
        // of its own for the things' order, its columns inside the visit's), and theirs.
        let (mut inner, mut inner_sector) = (sector_index, sector);
        let (mut inner_first, mut inner_end) = (first, end);
        loop {
            if scene.view.things == ThingsShown::On && !scene.map.things_in(inner).is_empty() {
                // Before the walls: the clip windows are still the ones the sector is seen
                // through.
                self.things.collect(
                    &scene.things,
                    stats.sector_visits as u16,
                    inner,
                    inner_first..inner_end,
                    &self.windows.windows().clip,
                );
            }
            if scene.map.slopes.is_empty() {
                self.draw_walls(scene, canvas, stats, inner_sector, inner_first, inner_end);
            } else {
                self.draw_walls_with_slopes(
                    scene,
                    canvas,
                    stats,
                    inner_sector,
                    inner_first,
                    inner_end,
                );
            }
            if scene.view.things == ThingsShown::On && self.has_middles(inner) {
                self.collect_middles(
                    scene,
                    canvas,
                    stats.sector_visits as u16,
                    inner,
                    inner_first,
                    inner_end,
                );
            }
            if self.see_through_used == 0 {
                break;
            }
            (inner, inner_sector, inner_first, inner_end) = self.next_seen_through(scene, stats);
        }
        debug_assert!(
            !self.windows.windows().ceiling[range.clone()].contains(&UNSET)
                && !self.windows.windows().floor[range].contains(&UNSET),
            "a column of sector {sector_index} owned by none of its walls"
        );
        if scene.layered && sector.links != 0 {
            self.open_layers(scene, (sector, sector_index), first, end);
        }
        let planes_started = (self.clock)();
        stats.wall_ticks += planes_started.wrapping_sub(walls_started);
        if sector.slope == NO_SLOPE {
            self.plane_job(scene, stats, sector, sector_index, first, end)
                .draw(canvas);
        } else {
            self.draw_sloped_planes(scene, canvas, stats, sector_index, first, end);
        }
        stats.plane_ticks += (self.clock)().wrapping_sub(planes_started);
    }

    /// The walls and strips of a visit's columns `[first, end)` on a map without slopes. Not
    /// inlined: its per-wall state stays off the stack frame of
    /// [`draw_sector`](Self::draw_sector), its caller for every visit.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram_render.draw_walls")]
    fn draw_walls(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        sector: &Sector,
        first: i32,
        end: i32,
    ) {
        self.walls_of::<false>(scene, canvas, stats, sector, first, end);
    }

    /// [`Renderer::draw_walls`] on a map with slopes: a wall whose sector or neighbour slopes
    /// goes to [`Renderer::draw_sloped_wall`]. Out of line and in ROM: a test and a call in
    /// the loop cost the IWRAM copy 400 bytes, which flat maps would carry for nothing.
    #[inline(never)]
    fn draw_walls_with_slopes(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        sector: &Sector,
        first: i32,
        end: i32,
    ) {
        self.walls_of::<true>(scene, canvas, stats, sector, first, end);
    }

    /// The loop of [`Renderer::draw_walls`] and [`Renderer::draw_walls_with_slopes`]; `SLOPES`
    /// says whether the map has any.
    #[inline(always)]
    fn walls_of<const SLOPES: bool>(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        sector: &Sector,
        first: i32,
        end: i32,
    ) {
        let walls = scene.map.sector_walls(sector);
        let mut ownership = Ownership::new(first, end);
        // The portals owning columns, for the walk (`WalkLevel::recorded`); a full record
        // stops recording, and the walk tests the visit's portals again instead.
        let mut recording = self.recording_portals;
        for (offset, wall) in walls.iter().enumerate() {
            let wall_index = sector.first_wall + offset as u16;
            let Some((a, b, start, stop)) = ownership.wall(scene, &self.vertices, wall) else {
                continue;
            };
            let mut seen_through = false;
            if wall.portal != NO_PORTAL && recording {
                match self.note_portal(scene, sector, wall, wall_index, start, stop) {
                    PortalNoted::SeenThrough => seen_through = true,
                    PortalNoted::Recorded => {}
                    PortalNoted::RecordFull => recording = false,
                }
            }
            if !seen_through {
                if SLOPES
                    && (sector.slope != NO_SLOPE
                        || wall.portal != NO_PORTAL
                            && scene.map.sectors[usize::from(wall.portal)].slope != NO_SLOPE)
                {
                    self.draw_sloped_wall(
                        scene,
                        canvas,
                        stats,
                        (sector, wall, wall_index),
                        (a, b),
                        start,
                        stop,
                    );
                    continue;
                }
                let projector = WallProjector::new(&scene.view.viewport, a, b);
                let mut job = WallJob::new(scene, sector, wall, wall_index);
                let stepper = projector.stepper(start);
                stats.wall_columns += (stop - start) as u32;
                let viewport = &scene.view.viewport;
                let heights = job.heights();
                let columns = stop - start;
                let (first, end, stepped) =
                    match SteppedWall::new(viewport, heights, &stepper, columns) {
                        Some(stepped) => (0, columns, Some(stepped)),
                        None => self.draw_clamped_runs(
                            scene, canvas, stats, &mut job, stepper, start, stop,
                        ),
                    };
                if let Some(stepped) = stepped {
                    self.draw_stepped_wall(
                        scene,
                        canvas,
                        stats,
                        &mut job,
                        stepped,
                        start + first,
                        start + end,
                    );
                }
            }
        }
        self.portals_recorded = recording;
    }

    /// Counts a visit of `sector_index` in `stats`, and whether the frame drew it before.
    #[inline(always)]
    fn count_visit(&mut self, stats: &mut FrameStats, sector_index: u16) {
        stats.sector_visits += 1;
        if let Some(word) = self.visited.get_mut(usize::from(sector_index) / 32) {
            let bit = 1u32 << (sector_index % 32);
            stats.repeat_visits += u32::from(*word & bit != 0);
            *word |= bit;
        }
    }

    /// Notes portal `wall` of `sector` (wall `wall_index` of the map), owning columns
    /// `start..stop`, for the walk. A portal into a neighbour with the same planes
    /// is seen through: the neighbour waits in [`Renderer::see_through`] and the portal is
    /// neither drawn nor recorded. That needs room in the record for every portal the waiting
    /// neighbours' walls and the sector's walls after this one may add, so that the walk never has to
    /// find the visit's portals again by testing them (it would not find the neighbours'):
    /// else the portal is recorded as any other. Out of line and in VRAM: once per portal wall,
    /// and only while the pass records its portals (the drawing walk's).
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".vram.note_portal")]
    fn note_portal(
        &mut self,
        scene: &Scene,
        sector: &Sector,
        wall: &Wall,
        wall_index: u16,
        start: i32,
        stop: i32,
    ) -> PortalNoted {
        let walls_after = usize::from(sector.first_wall + sector.wall_count - wall_index - 1);
        let noted = OwnedPortal {
            sector: wall.portal,
            start: start as i16,
            stop: stop as i16,
        };
        let neighbour = &scene.map.sectors[usize::from(wall.portal)];
        let room = PORTALS_RECORDED - usize::from(self.portals_used);
        let needed =
            walls_after + usize::from(self.see_through_walls) + usize::from(neighbour.wall_count);
        if wall.middle == NO_TEXTURE && same_planes(sector, neighbour) && needed <= room {
            if let Some(slot) = self.see_through.get_mut(usize::from(self.see_through_used)) {
                *slot = noted;
                self.see_through_used += 1;
                self.see_through_walls += neighbour.wall_count;
                return PortalNoted::SeenThrough;
            }
        }
        match self.portals.get_mut(usize::from(self.portals_used)) {
            Some(entry) => {
                *entry = noted;
                self.portals_used += 1;
                PortalNoted::Recorded
            }
            None => PortalNoted::RecordFull,
        }
    }

    /// The last neighbour waiting in [`Renderer::see_through`] (there is one), counted as a
    /// visit: its index, sector and columns. Out of line and in VRAM: once per neighbour.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".vram.next_seen_through")]
    fn next_seen_through<'m>(
        &mut self,
        scene: &Scene<'m, '_>,
        stats: &mut FrameStats,
    ) -> (u16, &'m Sector, i32, i32) {
        self.see_through_used -= 1;
        let portal = self.see_through[usize::from(self.see_through_used)];
        let neighbour = &scene.map.sectors[usize::from(portal.sector)];
        self.see_through_walls -= neighbour.wall_count;
        self.count_visit(stats, portal.sector);
        (
            portal.sector,
            neighbour,
            portal.start.into(),
            portal.stop.into(),
        )
    }

    /// A wall that [`SteppedWall`] cannot step whole: draws the columns nearest the eye (or at
    /// the far limit), which need the clamps, through [`Renderer::draw_clamped_wall`], and
    /// returns the run between them, `(first, end)` from `start`, with its [`SteppedWall`] if
    /// it has one (else that run is drawn here too). Each column is drawn alone, so the order
    /// of the runs changes no pixel. Out of line and in ROM, like the clamped loop, so the
    /// common walls' code is not disturbed.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn draw_clamped_runs(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        job: &mut WallJob,
        stepper: WallStepper,
        start: i32,
        stop: i32,
    ) -> (i32, i32, Option<SteppedWall>) {
        let columns = stop - start;
        let (first, end) = stepper.unclamped_columns(columns);
        let heights = job.heights();
        let mut clamped = |from: i32, to: i32| {
            if from < to {
                let at = stepper.advanced(from);
                self.draw_clamped_wall(scene, canvas, stats, job, at, start + from, start + to);
            }
        };
        clamped(0, first);
        clamped(end, columns);
        if first >= end {
            return (0, 0, None);
        }
        let middle = stepper.advanced(first);
        let stepped = SteppedWall::new(&scene.view.viewport, heights, &middle, end - first);
        if stepped.is_none() {
            clamped(first, end);
        }
        (first, end, stepped)
    }

    /// The columns `start..stop` of a wall that reaches the near plane or the far limit
    /// somewhere (a portal the eye stands in, a wall at the far limit): the stepper's 64-bit
    /// accumulators and clamps. Out of line and in ROM: few walls of a frame take it, and IWRAM
    /// has no room for a second copy of the column's code.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn draw_clamped_wall(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        job: &mut WallJob,
        mut stepper: WallStepper,
        start: i32,
        stop: i32,
    ) {
        let viewport = &scene.view.viewport;
        let kind = job.kind();
        let mut rows = WallRows::new(
            viewport,
            job.heights(),
            kind.reads_neighbour(),
            &stepper,
            stop - start,
        );
        for column in start..stop {
            let column_rows = rows.next_column().map(i32::from);
            self.wall_column(
                scene,
                canvas,
                stats,
                job,
                kind,
                || stepper.texturing(),
                column_rows,
                column,
            );
            stepper.step();
        }
    }

    /// The columns `start..stop` of a wall whose sector or neighbour slopes: each column's
    /// depth and position along the wall from the 64-bit stepper (with its clamps), then the
    /// rows of the heights there ([`SlopedHeights::rows`]). Out of line and in ROM, like the
    /// clamped loop: flat maps never come here, and their walls keep the ARM loop.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn draw_sloped_wall(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        (sector, wall, wall_index): (&Sector, &Wall, u16),
        (a, b): (EyePoint, EyePoint),
        start: i32,
        stop: i32,
    ) {
        let mut job = WallJob::new(scene, sector, wall, wall_index);
        let job = &mut job;
        let mut stepper = WallProjector::new(&scene.view.viewport, a, b).stepper(start);
        stats.wall_columns += (stop - start) as u32;
        let sloped = job.take_slopes(scene, wall);
        let viewport = &scene.view.viewport;
        let kind = job.kind();
        for column in start..stop {
            let (depth, along) = stepper.texturing();
            let rows = sloped.rows(viewport, &stepper, along);
            self.wall_column(
                scene,
                canvas,
                stats,
                job,
                kind,
                || (depth, along),
                rows,
                column,
            );
            stepper.step();
        }
    }

    /// The columns `start..stop` of a [`SteppedWall`] (most walls): drawn by the canvas's own
    /// wall loop where it has one (the GBA's, `asm/wall.s`), which stops where a strip needs
    /// another mip level and is started again after the renderer looks it up; else, and for
    /// walls it cannot take, by [`Renderer::draw_stepped_columns`], its twin.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn draw_stepped_wall(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        job: &mut WallJob,
        wall: SteppedWall,
        start: i32,
        stop: i32,
    ) {
        let mut resume = Some(WallResume {
            column: start,
            wall,
            pending: None,
        });
        // The canvas loops draw textured strips only; a strip of a missing texture is drawn
        // blank by the renderer's loop.
        if job.drawn_strips_textured() {
            resume = self.run_wall(scene, canvas, stats, job, wall, start, stop);
        }
        if let Some(WallResume {
            column,
            wall,
            pending,
        }) = resume
        {
            self.draw_stepped_columns(scene, canvas, stats, job, wall, pending, column, stop);
        }
    }

    /// [`Renderer::draw_stepped_wall`] through the canvas's own loop: the column and the wall's
    /// state where the renderer's loop must take over (the canvas has no loop, or a texture's
    /// levels are ones its kernels do not take), with that column's strips where its windows
    /// are drawn already; or `None` when every column is drawn.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn run_wall(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        job: &mut WallJob,
        wall: SteppedWall,
        start: i32,
        stop: i32,
    ) -> Option<WallResume> {
        let view = scene.view;
        let texturing = RunTexturing {
            length: job.length.to_bits(),
            x_offset: job.x_offset.to_bits(),
            inverse_focal_y: scene.inverse_focal_y as i32,
            horizon_row: view.viewport.horizon_y,
        };
        let light = run_light(job.sector.light, view.lighting, scene.assets.colormap);
        let kind = job.kind();
        job.take_first_levels(kind.draws(), &wall, scene.inverse_focal_y);
        let windows = self.windows.windows();
        let mut run = WallRun::new(
            wall.steps(),
            kind,
            start,
            stop,
            &mut windows.clip,
            &mut windows.ceiling,
            &mut windows.floor,
            texturing,
            light,
            job.strips.each_ref().map(StripTexture::run_level),
        )?;
        let resume = loop {
            match canvas.wall_run(&mut run) {
                None => break Some(run.column()),
                Some(WallRunEnd::Done) => break None,
                Some(WallRunEnd::MipLevel(ratio)) => {
                    let mut ready = true;
                    for (index, strip) in job.strips.iter_mut().enumerate() {
                        if strip.texture.is_some() {
                            strip.take_level(ratio);
                            run.set_strip(index, strip.run_level());
                            // A level whose height no kernel takes: the renderer's loop.
                            ready &= run.strip_ready(index);
                        }
                    }
                    if !ready {
                        break Some(run.column());
                    }
                }
            }
        };
        let (pixels, strips) = run.drawn();
        stats.column_pixels += pixels;
        stats.strips += strips;
        self.planes_seen |= run.planes_seen();
        resume.map(|column| WallResume {
            column,
            wall: SteppedWall::from_steps(run.steps()),
            pending: run.pending_strips(),
        })
    }

    /// The columns `start..stop` of a [`SteppedWall`]: its rows and texturing from 32-bit
    /// accumulators, column by column (the twin of the canvas loops of
    /// [`Renderer::draw_stepped_wall`]); first, where a canvas loop left the column `start`
    /// with its windows drawn, that column's `pending` strips. Out of line and in ROM: on the
    /// GBA only the walls the ARM loop cannot take come here.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn draw_stepped_columns(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        job: &mut WallJob,
        mut wall: SteppedWall,
        pending: Option<[(i32, i32); 2]>,
        mut start: i32,
        stop: i32,
    ) {
        if let Some(strips) = pending {
            let (depth, along) = wall.texturing();
            self.texture_column(scene, canvas, stats, job, depth, along, strips, start);
            wall.step();
            start += 1;
        }
        let kind = job.kind();
        for column in start..stop {
            let rows = wall.rows(kind.reads_neighbour());
            self.wall_column(
                scene,
                canvas,
                stats,
                job,
                kind,
                || wall.texturing(),
                rows,
                column,
            );
            wall.step();
        }
    }

    /// The planes of a visit of a sector with a slope ([`planes::PlaneJob::draw_with_slopes`]):
    /// out of line and in ROM, so the flat sectors' visit in IWRAM is what it was.
    #[inline(never)]
    fn draw_sloped_planes(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        sector_index: u16,
        first: i32,
        end: i32,
    ) {
        let sector = &scene.map.sectors[usize::from(sector_index)];
        let planes = scene.map.planes(sector);
        self.plane_job(scene, stats, sector, sector_index, first, end)
            .draw_with_slopes(canvas, planes);
    }

    fn plane_job<'r>(
        &'r mut self,
        scene: &'r Scene,
        stats: &'r mut FrameStats,
        sector: &'r Sector,
        sector_index: u16,
        first: i32,
        end: i32,
    ) -> planes::PlaneJob<'r> {
        let windows = self.windows.windows();
        planes::PlaneJob {
            view: scene.view,
            assets: scene.assets,
            sector,
            sector_index,
            first: first as usize,
            // A plane whose walls left no window with rows has nothing to draw: no windows.
            ceiling: if self.planes_seen & CEILING_SEEN != 0 {
                &windows.ceiling[first as usize..end as usize]
            } else {
                &[]
            },
            floor: if self.planes_seen & FLOOR_SEEN != 0 {
                &windows.floor[first as usize..end as usize]
            } else {
                &[]
            },
            span_start: &mut windows.span_start,
            stats,
            column_angles: &windows.column_angles,
        }
    }

    /// One column of a wall: its plane windows, the clip window it leaves, its strips.
    /// `rows` are the column's rows of the wall's heights ([`WallJob::heights`]).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn wall_column(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        job: &mut WallJob,
        kind: WallKind,
        texturing: impl FnOnce() -> (Fx24_8, Fx2_30),
        rows: [i32; ROW_HEIGHTS],
        column: i32,
    ) {
        let (strips, planes_seen) =
            column_windows(self.windows.windows(), kind, rows, column as usize);
        self.planes_seen |= planes_seen;
        if strips.iter().all(|(top, bottom)| top >= bottom) {
            // Nothing of the wall is drawn in this column (an open portal, or a clipped strip):
            // its texture column is not needed.
            return;
        }
        let (depth, along) = texturing();
        self.texture_column(scene, canvas, stats, job, depth, along, strips, column);
    }

    /// The strips of one wall column, rows `strips[k].0..strips[k].1` of `job.strips[k]`, at
    /// `depth` and `along` the wall: its texture column, mip level and light, then each strip.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn texture_column(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        job: &mut WallJob,
        depth: Fx24_8,
        along: Fx2_30,
        strips: [(i32, i32); 2],
        column: i32,
    ) {
        let u = Fx24_8::from_bits(
            ((i64::from(along.to_bits()) * i64::from(job.length.to_bits())) >> 30) as i32,
        ) + job.x_offset;
        let depth_over_focal = i64::from(depth.to_bits()) * scene.inverse_focal_y;
        debug_assert_eq!(
            (depth_over_focal >> 38) as i32,
            mip_ratio(i64::from(depth.to_bits()), scene.inverse_focal_y)
        );
        let strip = StripColumn {
            u,
            column: column as usize,
            // z'/d_y in 24.8 × 2^30, through the 2.30 reciprocal of d_y (a table entry).
            depth_over_focal,
            // The same product as `depth_over_focal`: `mip_ratio` is its top bits.
            mip_ratio: (depth_over_focal >> 38) as i32,
            colormap: light_row(job.sector.light, depth.to_int_floor(), scene.view.lighting)
                .map(|row| &scene.assets.colormap[row]),
        };
        for (texture, (top, bottom)) in job.strips.iter_mut().zip(strips) {
            self.draw_strip(scene, canvas, stats, &strip, texture, top, bottom);
        }
    }

    /// Draws rows `top..bottom` of one wall column with the strip texture `texture`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn draw_strip(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        strip: &StripColumn,
        texture: &mut StripTexture,
        top: i32,
        bottom: i32,
    ) {
        if top >= bottom {
            return;
        }
        let count = (bottom - top) as usize;
        stats.column_pixels += count as u32;
        stats.strips += 1;
        canvas.set_surface(texture.surface);
        let view = scene.view;
        let colormap = strip.colormap;
        let Some(texture_image) = texture.texture else {
            let column = ColumnTexture {
                texels: &BLANK_COLUMN,
                log2_height: 3,
                v: 0,
                dv: 0,
                colormap: None,
            };
            canvas.column(strip.column, top as usize, count, &column);
            return;
        };
        let cached = &mut texture.level;
        if !(cached.ratio_low..=cached.ratio_high).contains(&strip.mip_ratio) {
            *cached = StripLevel::of(texture_image, strip.mip_ratio);
        }
        let StripLevel {
            level,
            width_log2,
            height_log2,
            texels,
            ..
        } = *cached;
        let u_texel = (strip.u.to_int_floor() >> level) & ((1 << width_log2) - 1);
        let column_texels =
            &texels[(u_texel as usize) << height_log2..((u_texel as usize) + 1) << height_log2];
        // v (texels at level 0) of row r: anchor − eye + y_offset + (r + ½ − cy)·z/d_y; as a
        // fraction of the texture height in 0.32 it is the same at every mip level.
        let base_log2 = u32::from(texture_image.height_log2);
        // Within ±(2·160 + 1): one 32-bit factor, so the product takes two multiplies, not three.
        let twice_row_offset = 2 * (top - view.viewport.horizon_y) + 1;
        // v in 24.8 texels; then scale to 0.32 of the height: × 2^(24 − log2 height), of which
        // only the low 32 bits are kept, and those come from v's low 32 bits alone.
        let v_bits =
            texture.eye_to_anchor + ((i64::from(twice_row_offset) * strip.depth_over_focal) >> 31);
        let v = (v_bits as u32) << (24 - base_log2);
        let dv = (strip.depth_over_focal >> (6 + base_log2)) as u32;
        let column = ColumnTexture {
            texels: column_texels,
            log2_height: height_log2,
            v,
            dv,
            colormap,
        };
        canvas.column(strip.column, top as usize, count, &column);
    }
}

/// Column `x` of a wall whose rows there are `rows` ([`WallJob::heights`]): sets its ceiling
/// and floor windows and the clip window it leaves for the sectors behind it, and returns the
/// rows `(top, bottom)` of its two strips (`job.strips`; `top >= bottom` where not drawn).
#[inline(always)]
fn column_windows(
    windows: &mut ColumnWindows,
    kind: WallKind,
    rows: [i32; ROW_HEIGHTS],
    x: usize,
) -> ([(i32, i32); 2], u32) {
    let [ceiling, floor, neighbour_ceiling, neighbour_floor] = rows;
    let clip = windows.clip[x];
    let (clip_top, clip_bottom) = (i32::from(clip.top), i32::from(clip.bottom));
    let ceiling_row = ceiling.max(clip_top);
    let floor_row = floor.min(clip_bottom);
    let window = |top: i32, bottom: i32| Window {
        top: top as i16,
        bottom: bottom as i16,
    };
    let (ceiling_window, floor_window) = (
        window(clip_top, ceiling_row.min(clip_bottom)),
        window(floor_row.max(clip_top), clip_bottom),
    );
    windows.ceiling[x] = ceiling_window;
    windows.floor[x] = floor_window;
    let planes_seen = if ceiling_window.is_empty() {
        0
    } else {
        CEILING_SEEN
    } | if floor_window.is_empty() {
        0
    } else {
        FLOOR_SEEN
    };
    // The rows of the column's strips (`job.strips`, empty where not drawn), and the clip
    // window the column leaves for the sectors behind it.
    let strips = match kind {
        WallKind::Solid => {
            windows.clip[x] = Window::EMPTY;
            [(ceiling_row, floor_row), (0, 0)]
        }
        // An opening with no strip (the neighbour's ceiling and floor are not inside this
        // sector's): the neighbour's rows are not read.
        WallKind::Opening => {
            windows.clip[x] = window(ceiling_row, floor_row.max(ceiling_row));
            [(0, 0), (0, 0)]
        }
        WallKind::Portal { upper, lower } => {
            let neighbour_ceiling_row = neighbour_ceiling
                .max(ceiling_row)
                .min(floor_row.max(ceiling_row));
            let neighbour_floor_row = neighbour_floor
                .max(neighbour_ceiling_row.min(floor_row))
                .min(floor_row);
            // Where no upper strip is drawn (the neighbour's ceiling is not lower, or both
            // show the sky), the neighbour gets the rows down from this sector's ceiling
            // line: its own ceiling (sky) fills them, and no row between the two ceiling
            // lines is left undrawn.
            let opening_top = if upper {
                neighbour_ceiling_row
            } else {
                ceiling_row
            };
            let opening_bottom = if lower {
                neighbour_floor_row
            } else {
                floor_row
            };
            windows.clip[x] = window(opening_top, opening_bottom.max(opening_top));
            [
                if upper {
                    (ceiling_row, neighbour_ceiling_row)
                } else {
                    (0, 0)
                },
                if lower {
                    (neighbour_floor_row, floor_row)
                } else {
                    (0, 0)
                },
            ]
        }
    };
    (strips, planes_seen)
}

/// Where the renderer's own loop takes over a wall from a canvas loop: the column, the wall's
/// accumulators there, and that column's strips where the canvas loop drew its windows.
struct WallResume {
    column: i32,
    wall: SteppedWall,
    pending: Option<[(i32, i32); 2]>,
}

/// The eye-space ends of a sector's walls and the columns of `[first, end)` each owns, one
/// wall after the other: a wall's end is the next wall's start, so each vertex is transformed
/// and split once per loop (twice for the loop's first vertex at most).
#[derive(Clone, Copy)]
struct Ownership {
    first: i32,
    end: i32,
    last: Option<(u16, EyePoint, VertexSplit)>,
}

impl Ownership {
    const fn new(first: i32, end: i32) -> Ownership {
        Ownership {
            first,
            end,
            last: None,
        }
    }

    /// Vertex `index` in eye space and its split of the columns. Out of line: the portal walk
    /// and the wall pass both call it, and a copy in each would not fit IWRAM.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram_render.ownership_vertex")]
    fn vertex(&self, scene: &Scene, vertices: &VertexCache, index: u16) -> (EyePoint, VertexSplit) {
        let (point, first_column) = vertices.get(scene, index);
        let split = if first_column == NO_COLUMN {
            // At or behind the eye: split by bisection, the exact point computed again only for
            // a near-tie.
            VertexSplit::new_exact(
                &scene.view.viewport,
                point,
                || scene.view.eye.to_eye_exact(vertex(scene.map, index)),
                self.first,
                self.end,
            )
        } else {
            VertexSplit::from_first_column(first_column, self.first, self.end)
        };
        (point, split)
    }

    /// The eye-space ends of `wall` and the columns of `[first, end)` it owns, if any.
    fn wall(
        &mut self,
        scene: &Scene,
        vertices: &VertexCache,
        wall: &Wall,
    ) -> Option<(EyePoint, EyePoint, i32, i32)> {
        let (a, a_split) = match self.last {
            Some((index, point, split)) if index == wall.start => (point, split),
            _ => self.vertex(scene, vertices, wall.start),
        };
        let (b, b_split) = self.vertex(scene, vertices, wall.end);
        self.last = Some((wall.end, b, b_split));
        let (start, stop) = owned_columns_in(a_split, b_split, self.first, self.end);
        (start < stop).then_some((a, b, start, stop))
    }
}

/// What every column of one wall shares: computed once per wall, not per column.
struct WallJob<'s> {
    sector: &'s Sector,
    length: Fx24_8,
    x_offset: Fx24_8,
    /// The sector's ceiling and floor heights above the eye.
    ceiling_above_eye: Fx24_8,
    floor_above_eye: Fx24_8,
    /// The wall's texture (solid) or its upper and lower strips' (portal).
    strips: [StripTexture<'s>; 2],
    portal: Option<PortalJob>,
}

impl<'s> WallJob<'s> {
    /// Solid, or a portal with or without strips: what its columns draw and leave open.
    fn kind(&self) -> WallKind {
        match &self.portal {
            None => WallKind::Solid,
            Some(portal) => WallKind::portal(portal.upper_drawn, portal.lower_drawn),
        }
    }

    /// Whether every strip its columns draw (a solid wall's, a portal's upper and lower where
    /// drawn) has a texture.
    fn drawn_strips_textured(&self) -> bool {
        let [first, second] = self.kind().draws();
        let [upper, lower] = &self.strips;
        (!first || upper.texture.is_some()) && (!second || lower.texture.is_some())
    }

    /// The heights above the eye whose rows each column needs, in the order of
    /// [`WallRows::next_column`]'s rows: the sector's ceiling and floor, then the neighbour's
    /// (a solid wall repeats its own: the rows are computed and not read).
    fn heights(&self) -> [Fx24_8; ROW_HEIGHTS] {
        let (neighbour_ceiling, neighbour_floor) = match &self.portal {
            Some(portal) => (portal.ceiling_above_eye, portal.floor_above_eye),
            None => (self.ceiling_above_eye, self.floor_above_eye),
        };
        [
            self.ceiling_above_eye,
            self.floor_above_eye,
            neighbour_ceiling,
            neighbour_floor,
        ]
    }
}

/// A portal's neighbour, as its columns need it.
#[derive(Clone, Copy)]
struct PortalJob {
    ceiling_above_eye: Fx24_8,
    floor_above_eye: Fx24_8,
    /// The neighbour's ceiling is lower, and not both show the sky: an upper strip, and the
    /// opening's top is its row. Between two sky sectors the lower ceiling's strip is this
    /// sector's sky: the wall's ceiling is the neighbour's (see [`WallJob::new`]).
    upper_drawn: bool,
    /// The neighbour's floor is higher: a lower strip, and the opening's bottom is its row.
    lower_drawn: bool,
}

/// One strip's texture, surface and vertical anchor.
struct StripTexture<'s> {
    texture: Option<&'s Texture<'s>>,
    surface: Surface,
    /// `anchor − eye_z + y_offset` in 24.8 texels: v at the eye's height.
    eye_to_anchor: i64,
    /// The mip level the strip's last column took, reused while the columns' depth keeps
    /// within it (neighbouring columns mostly do).
    level: StripLevel<'s>,
}

/// A strip's mip level and what its columns need of it, with the range of [`mip_ratio`]s that
/// select it.
#[derive(Clone, Copy)]
struct StripLevel<'s> {
    /// The ratios `ratio_low..=ratio_high` select this level (empty until a column asks).
    ratio_low: i32,
    ratio_high: i32,
    level: u8,
    width_log2: u32,
    height_log2: u32,
    texels: &'s [u8],
}

impl<'s> StripTexture<'s> {
    /// Keeps the level that mip ratio `ratio` selects (looked up if the kept one does not).
    fn take_level(&mut self, ratio: i32) {
        if let Some(texture) = self.texture {
            if !(self.level.ratio_low..=self.level.ratio_high).contains(&ratio) {
                self.level = StripLevel::of(texture, ratio);
            }
        }
    }

    /// The kept level as a canvas's wall loop takes it (an empty range until one is kept).
    fn run_level(&self) -> StripRunLevel<'s> {
        let level = &self.level;
        StripRunLevel {
            eye_to_anchor: self.eye_to_anchor,
            base_height_log2: self
                .texture
                .map_or(0, |texture| u32::from(texture.height_log2)),
            ratio_low: level.ratio_low,
            ratio_high: level.ratio_high,
            level: u32::from(level.level),
            width_log2: level.width_log2,
            height_log2: level.height_log2,
            texels: level.texels,
        }
    }
}

impl<'s> StripLevel<'s> {
    const NONE: StripLevel<'static> = StripLevel {
        ratio_low: 1,
        ratio_high: 0,
        level: 0,
        width_log2: 0,
        height_log2: 0,
        texels: &[],
    };

    /// The level [`mip_level_of_ratio`] picks for `ratio`, and the ratios that pick it too.
    /// Once a wall and strip, and again at each change of level: out of line, in IWRAM (from
    /// the cartridge it cost 4,060 cycles a frame of the 120×80 fly-through's mean).
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram_render.strip_level_of")]
    fn of(texture: &Texture<'s>, ratio: i32) -> StripLevel<'s> {
        let level = mip_level_of_ratio(
            ratio,
            texture.mip_count,
            texture.width_log2,
            texture.height_log2,
        );
        let deepest = mip_level_of_ratio(
            i32::MAX,
            texture.mip_count,
            texture.width_log2,
            texture.height_log2,
        );
        let (ratio_low, ratio_high) = mip_ratios_of_level(level, 0, deepest);
        StripLevel {
            ratio_low,
            ratio_high,
            level,
            width_log2: u32::from(texture.level_width_log2(level)),
            height_log2: u32::from(texture.level_height_log2(level)),
            texels: texture.wall_level(level),
        }
    }
}

impl<'s> WallJob<'s> {
    /// The drawn strips take a level for the depth of `wall`'s current column: a canvas loop
    /// started without one would stop at once to ask for it, and most walls keep their first
    /// column's level to their end. The mip ratio `z'/d_y` is `(1/d_y)/(1/z')`: taken here to
    /// its power of two by shifts, no reciprocal. A level missed near a power (the loop's own
    /// ratio is rounded) stops the loop at that column as no level did, so no pixel depends
    /// on it. Once per wall, in IWRAM (from the room the column kernels' banks gave back: it
    /// was the VRAM code's hottest by its bytes).
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram_render.wall_first_levels")]
    fn take_first_levels(&mut self, drawn: [bool; 2], wall: &SteppedWall, inverse_focal_y: i64) {
        // Both in 2.30, positive: 32-bit words.
        let inverse_depth = wall.steps().inverse_depth.max(1) as u32;
        let inverse_focal_y = inverse_focal_y.max(1) as u32;
        // The largest power of two with `inverse_depth · ratio ≤ inverse_focal_y` (0 if none).
        let mut ratio = 0i32;
        if inverse_depth <= inverse_focal_y {
            ratio = 1;
            let mut scaled = inverse_depth;
            while scaled <= inverse_focal_y >> 1 {
                scaled <<= 1;
                ratio <<= 1;
            }
        }
        for (strip, drawn) in self.strips.iter_mut().zip(drawn) {
            if drawn {
                strip.take_level(ratio);
            }
        }
    }

    /// Inlined into both callers: the wall loop's copy stays in IWRAM (with two callers and no
    /// hint it went to the cartridge, called for every wall).
    #[inline(always)]
    fn new(scene: &Scene<'s, 's>, sector: &'s Sector, wall: &'s Wall, wall_index: u16) -> Self {
        let view = scene.view;
        let above_eye = |height: i32| Fx24_8::from_int(height) - view.eye_z;
        let strip = |texture: u16, anchor: i32, surface: Surface| StripTexture {
            texture: scene.assets.textures.get(usize::from(texture)),
            surface,
            eye_to_anchor: i64::from(above_eye(anchor).to_bits()) + (i64::from(wall.y_offset) << 8),
            level: StripLevel::NONE,
        };
        let (strips, portal, ceiling) = if wall.portal == NO_PORTAL {
            let texture = scene.map.solid_texture(wall_index, wall);
            (
                [
                    strip(texture, sector.ceil_z, Surface::Wall(wall_index)),
                    strip(texture, sector.ceil_z, Surface::Wall(wall_index)),
                ],
                None,
                sector.ceil_z,
            )
        } else {
            let neighbour = &scene.map.sectors[usize::from(wall.portal)];
            let sky_over_sky = is_sky(sector) && is_sky(neighbour);
            (
                [
                    strip(
                        wall.upper_texture,
                        sector.ceil_z,
                        Surface::Upper(wall_index),
                    ),
                    strip(
                        wall.lower_texture,
                        neighbour.floor_z,
                        Surface::Lower(wall_index),
                    ),
                ],
                Some(PortalJob {
                    ceiling_above_eye: above_eye(neighbour.ceil_z),
                    floor_above_eye: above_eye(neighbour.floor_z),
                    upper_drawn: neighbour.ceil_z < sector.ceil_z && !sky_over_sky,
                    lower_drawn: neighbour.floor_z > sector.floor_z,
                }),
                // Between two sky sectors the strip under the higher ceiling is this sector's
                // sky (Doom's sky hack, `worldtop = worldhigh`; the oracle's rule): its ceiling
                // reaches down to the neighbour's on this wall, so the opening stops there and
                // a neighbour's ceiling below the eye shows nothing beyond it through the strip.
                // Never below this sector's floor: a neighbour whose ceiling is lower shows only
                // sky over this floor's edge.
                if sky_over_sky {
                    sector.ceil_z.min(neighbour.ceil_z).max(sector.floor_z)
                } else {
                    sector.ceil_z
                },
            )
        };
        WallJob {
            sector,
            length: wall_length(wall),
            x_offset: Fx24_8::from_int(i32::from(wall.x_offset)),
            ceiling_above_eye: above_eye(ceiling),
            floor_above_eye: above_eye(sector.floor_z),
            strips,
            portal,
        }
    }

    /// The heights at both ends of `wall`, whose sector or neighbour slopes, which its columns
    /// step instead of [`WallJob::heights`]; and which strips show somewhere along it (a strip
    /// shows where the neighbour's ceiling is lower, or its floor higher, at either end; the
    /// columns clip it where it is not). The rules of [`WallJob::new`] at each end.
    fn take_slopes(&mut self, scene: &Scene, wall: &Wall) -> SlopedHeights {
        let map = scene.map;
        let eye_z = scene.view.eye_z.to_bits();
        let sector = self.sector;
        let sky_over_sky = |neighbour: &Sector| is_sky(sector) && is_sky(neighbour);
        let heights_at = |index: u16| {
            let end = map.vertices[usize::from(index)];
            let (x, y) = (end.x * 256, end.y * 256);
            let (floor, ceiling) = map.heights_fx8_at(sector, x, y);
            let (neighbour_floor, neighbour_ceiling) = match wall.neighbour() {
                Some(next) => map.heights_fx8_at(&map.sectors[usize::from(next)], x, y),
                None => (floor, ceiling),
            };
            let ceiling = match wall.neighbour() {
                Some(next) if sky_over_sky(&map.sectors[usize::from(next)]) => {
                    ceiling.min(neighbour_ceiling).max(floor)
                }
                _ => ceiling,
            };
            [ceiling, floor, neighbour_ceiling, neighbour_floor]
        };
        let (start, end) = (heights_at(wall.start), heights_at(wall.end));
        if let (Some(portal), Some(next)) = (&mut self.portal, wall.neighbour()) {
            let neighbour = &map.sectors[usize::from(next)];
            let own = |ends: &[i32; 4]| (ends[0], ends[1]);
            portal.upper_drawn =
                !sky_over_sky(neighbour) && [start, end].iter().any(|ends| ends[2] < own(ends).0);
            portal.lower_drawn = [start, end].iter().any(|ends| ends[3] > own(ends).1);
        }
        SlopedHeights {
            start: start.map(|height| Fx24_8::from_bits(height - eye_z)),
            rise: core::array::from_fn(|index| end[index] - start[index]),
        }
    }
}

/// What one wall column's strips share.
struct StripColumn<'s> {
    u: Fx24_8,
    column: usize,
    /// `z'` (24.8 bits) × the 2.30 reciprocal of `d_y`: `z'/d_y` in 24.8 × 2^30.
    depth_over_focal: i64,
    /// The mip rule's `floor(z'/d_y)` ([`mip_ratio`]).
    mip_ratio: i32,
    colormap: Option<&'s [u8; 256]>,
}

/// Texels for a surface whose texture is missing: palette index 0, as the oracle draws it.
static BLANK_COLUMN: [u8; 8] = [0; 8];

fn vertex(map: &MapTables, index: u16) -> WorldPoint {
    let v = map.vertices[usize::from(index)];
    WorldPoint::from_int(v.x, v.y)
}

/// Whether sectors `a` and `b` have the same floor and ceiling: heights, flats and light. A
/// portal between two such (without a middle image) shows nothing of itself: no strip, and the
/// planes on either side meet in one (Doom's `R_AddLine` leaves such a line out).
pub fn same_planes(a: &Sector, b: &Sector) -> bool {
    // A floor or ceiling portal is entered from its own sector's windows: never merged.
    (a.links | b.links) == 0
        && (
            a.floor_z,
            a.ceil_z,
            a.floor_texture,
            a.ceil_texture,
            a.light,
        ) == (
            b.floor_z,
            b.ceil_z,
            b.floor_texture,
            b.ceil_texture,
            b.light,
        )
}

/// A wall's length in 24.8: the map compiler's ([`Wall::length_fx8`]).
fn wall_length(wall: &Wall) -> Fx24_8 {
    Fx24_8::from_bits(wall.length_fx8)
}

/// The mip level for depth `depth`: `floor(log2(depth / focal_y))`, at least 0, below
/// `mip_count`, and keeping both sides at least 8 texels (the smallest column kernel).
#[inline]
pub fn mip_level(
    depth: Fx24_8,
    focal_y: i32,
    mip_count: u8,
    width_log2: u8,
    height_log2: u8,
) -> u8 {
    let inverse_focal_y = i64::from(recip_small(focal_y as u32).to_bits());
    mip_level_of_ratio(
        mip_ratio(i64::from(depth.to_bits()), inverse_focal_y),
        mip_count,
        width_log2,
        height_log2,
    )
}

/// `floor(depth / focal_y)` for the mip rule, from the depth's 24.8 bits and the 2.30
/// reciprocal of `focal_y` (its bits): no divide.
#[inline(always)]
pub(crate) fn mip_ratio(depth_bits: i64, inverse_focal_y: i64) -> i32 {
    ((depth_bits * inverse_focal_y) >> 38) as i32
}

/// [`mip_level`] from its [`mip_ratio`].
#[inline(always)]
pub(crate) fn mip_level_of_ratio(ratio: i32, mip_count: u8, width_log2: u8, height_log2: u8) -> u8 {
    let mut level = 0u8;
    while (ratio >> (level + 1)) > 0 {
        level += 1;
    }
    let smallest_side = width_log2.min(height_log2);
    level
        .min(mip_count.saturating_sub(1))
        .min(smallest_side.saturating_sub(3))
}

/// The [`mip_ratio`]s that select `level`, for a rule whose levels run from `shallowest` to
/// `deepest`: unclamped, a level L ≥ 1 is floor(log2(ratio)), the ratios 2^L..2^(L+1) − 1; the
/// shallowest level takes every ratio below those of the next, and the deepest every ratio from
/// its own power up. Lets a strip or a plane keep its level while the ratio stays in range.
#[inline]
pub(crate) const fn mip_ratios_of_level(level: u8, shallowest: u8, deepest: u8) -> (i32, i32) {
    (
        if level <= shallowest {
            i32::MIN
        } else {
            1 << level
        },
        if level >= deepest {
            i32::MAX
        } else {
            (1 << (level + 1)) - 1
        },
    )
}

pub(crate) fn is_sky(sector: &Sector) -> bool {
    sector.ceil_texture == SKY
}

/// Whether the binary angle `angle` (within ±45°) is at most the angle of the slope
/// `q / twice_focal`: `tan(angle) ≤ q/2d  ⇔  sin·2d ≤ q·cos` (cos > 0 there).
fn angle_within_slope(angle: i32, q: i32, twice_focal: i32) -> bool {
    let (sin, cos) = crate::math::Angle::from_bits(angle as u16).sin_cos();
    i64::from(sin.to_bits()) * i64::from(twice_focal) <= i64::from(q) * i64::from(cos.to_bits())
}

/// Angles within ±45° (a quarter turn is 16,384): the field of view is 90°.
const COLUMN_ANGLE_LIMIT: i32 = 8192;

/// The largest angle of `low..=high` within the slope `q / twice_focal`, `low` if none above
/// it is (`low` itself is not tested): bisection on the sine table.
fn bisect_column_angle(mut low: i32, mut high: i32, q: i32, twice_focal: i32) -> i32 {
    while low < high {
        let middle = (low + high + 1).div_euclid(2);
        if angle_within_slope(middle, q, twice_focal) {
            low = middle;
        } else {
            high = middle - 1;
        }
    }
    low
}

/// The binary angle (65,536 per turn) from the view direction to a column's ray, whose slope is
/// `q / twice_focal` (`q = 2(c − cx) + 1`): the largest angle with `tan ≤` the slope, found by
/// bisection on the sine table, so the sky needs no arctangent table. [`column_angles`] finds
/// the same angles for a whole row of columns faster.
pub fn column_angle(q: i32, twice_focal: i32) -> i16 {
    bisect_column_angle(-COLUMN_ANGLE_LIMIT, COLUMN_ANGLE_LIMIT, q, twice_focal) as i16
}

/// [`column_angle`] of every column of `angles` (column 0 first) for a viewport centred on
/// column `centre_x` with focal length `focal_x`. Once per resolution, inside the first frame
/// drawn at it; the bisection's fourteen sines a column made the switch to 240 wide stall
/// that frame by about 780,000 cycles from the cartridge (`pc-profile` over the bench scene's
/// switch from 120×160 to 240×160; about 85,000 now). Here each angle is searched for around the one
/// its two neighbours on the left point to (they step almost evenly), a few sines a column,
/// and bisected inside the bracket that search finds, so the angles are the bisection's.
pub fn column_angles(centre_x: i32, focal_x: i32, angles: &mut [i16]) {
    let twice_focal = 2 * focal_x;
    let (mut before, mut step) = (None::<i32>, 0i32);
    for (column, angle) in angles.iter_mut().enumerate() {
        let q = 2 * (column as i32 - centre_x) + 1;
        let found = match before {
            None => bisect_column_angle(-COLUMN_ANGLE_LIMIT, COLUMN_ANGLE_LIMIT, q, twice_focal),
            Some(previous) => {
                // The answer is the largest angle within the slope, or the lower limit: at
                // least `low` once `low` is within it (or the limit), at most `high` once
                // `high + 1` is not (or `high` is the limit). From the guess, each bound moves
                // out by doubling strides until it holds, then the range is bisected.
                let guess = (previous + step).clamp(-COLUMN_ANGLE_LIMIT, COLUMN_ANGLE_LIMIT);
                let beyond = |angle: i32| {
                    angle > -COLUMN_ANGLE_LIMIT && !angle_within_slope(angle, q, twice_focal)
                };
                let (mut low, mut high) = (guess, guess);
                let mut stride = 1;
                while beyond(low) {
                    high = low - 1;
                    low = (low - stride).max(-COLUMN_ANGLE_LIMIT);
                    stride *= 2;
                }
                stride = 1;
                while high < COLUMN_ANGLE_LIMIT && !beyond(high + 1) {
                    low = high + 1;
                    high = (high + stride).min(COLUMN_ANGLE_LIMIT);
                    stride *= 2;
                }
                bisect_column_angle(low, high, q, twice_focal)
            }
        };
        if let Some(previous) = before {
            step = found - previous;
        }
        before = Some(found);
        *angle = found as i16;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The row search finds the bisection's angle in every column of every resolution, and of
    /// viewports of other widths and focal lengths.
    #[test]
    fn column_angles_are_the_bisection_s() {
        let resolutions = crate::frame::Resolution::ALL
            .iter()
            .map(|resolution| (resolution.width() as i32, resolution.height() as i32));
        let others = [(2, 2), (7, 5), (64, 160), (239, 16), (240, 2)];
        for (width, height) in resolutions.chain(others) {
            let viewport = crate::math::Viewport::new(width, height);
            let mut angles = vec![0i16; width as usize];
            column_angles(viewport.centre_x(), viewport.focal_x, &mut angles);
            for (column, &angle) in angles.iter().enumerate() {
                let q = 2 * (column as i32 - viewport.centre_x()) + 1;
                assert_eq!(
                    angle,
                    column_angle(q, 2 * viewport.focal_x),
                    "width {width}, column {column}"
                );
            }
        }
        // Focal lengths the viewports do not have: wide and narrow rows of slopes.
        for focal_x in [1, 3, 17, 60, 120, 1000, 30000] {
            let mut angles = vec![0i16; 240];
            column_angles(120, focal_x, &mut angles);
            for (column, &angle) in angles.iter().enumerate() {
                let q = 2 * (column as i32 - 120) + 1;
                assert_eq!(
                    angle,
                    column_angle(q, 2 * focal_x),
                    "focal {focal_x}, column {column}"
                );
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(5000))]
        /// A level's ratio range holds every ratio that picks the level and none other: a strip
        /// or plane that keeps its level while the ratio stays in range picks what the rule
        /// would pick afresh.
        #[test]
        fn a_level_s_ratio_range_is_exactly_the_ratios_that_pick_it(
            ratio in prop_oneof![0i32..4096, 0i32..=i32::MAX],
            mip_count in 1u8..=9,
            width_log2 in 3u8..=8,
            height_log2 in 3u8..=8,
            shallowest in 0u8..=3,
        ) {
            let pick = |ratio: i32| {
                mip_level_of_ratio(ratio, mip_count, width_log2, height_log2).max(shallowest)
            };
            let level = pick(ratio);
            let (low, high) = mip_ratios_of_level(level, shallowest, pick(i32::MAX));
            prop_assert!((low..=high).contains(&ratio));
            prop_assert_eq!(pick(low.max(0)), level);
            prop_assert_eq!(pick(high), level);
            if low > 0 {
                prop_assert_ne!(pick(low - 1), level);
            }
            if high < i32::MAX {
                prop_assert_ne!(pick(high + 1), level);
            }
        }
    }
}
