//! Checks a parsed map against the limits and the geometry rules and builds its tables.
//!
//! Checks run in stages, each reporting every error it finds; a stage runs only when the
//! previous ones passed, because its checks rely on them (geometry needs coordinates in range,
//! portal pairing needs closed convex sectors): values and names, then each sector's outline,
//! then portals, then the player and things.

use std::collections::HashMap;

use portalcast_format::limits::{
    HEIGHT_MAX, HEIGHT_MIN, LIGHTS_MAX, MOVERS_MAX, PORTAL_DEPTH_MAX, TEXTURE_COORD_MAX,
    THINGS_MAX, TRIGGERS_MAX, WORLD_COORD_MAX,
};
use portalcast_format::{
    find_twin, LayerLink, Light, MapTables, Mover, Plane, PlayerStart, Sector, SectorSlope, Thing,
    Trigger, Vertex, Wall, LINK_CEILING, LINK_FLOOR, MOVER_CRUSHER, MOVER_DOOR, MOVER_LIFT,
    MOVER_ON_TOUCH, MOVER_ON_USE, MOVER_PLATFORM, NO_LINK, NO_PORTAL, NO_SLOPE, NO_TEXTURE,
    NO_TWIN, SKY, THING_HANGING, THING_SOLID, THING_TRANSLUCENT, TRIGGER_LINE, TRIGGER_SWITCH,
    WALL_MIDDLE_BLOCKS, WALL_MIDDLE_TRANSLUCENT, WALL_SWITCH,
};

use crate::diag::{Loc, Located};
use crate::geometry::{cross, dot, double_area, segments_touch, Point};
use crate::source::{
    CeilingSource, MoverKind, SourceMap, SourceMover, SourcePlace, SourceSector, SourceThing,
    SourceWall, Spanned,
};

/// What an asset directory offers, by name; maps are checked against it. Texture and sprite set
/// indices in a [`CompiledMap`] built against a catalog are positions in its sorted name lists.
/// A thing names a sprite set (`sprites/NAME.png`, or its animation frames or rotations:
/// `docs/MAP_FORMAT.md`, "Sprites").
///
/// The checks that need a sprite's size (a thing's footprint and height) use the sizes given with
/// [`Catalog::with_sprite_size`]; a set without one counts as 0×0 there.
/// [`crate::compile_dir`] checks things against the sprite images themselves. A portal's middle
/// image (`mid=`) must be a still set: one frame, no rotations; a set counts as still unless
/// [`Catalog::with_sprite_frames`] says otherwise ([`crate::compile_dir`] gives every set's, from
/// its file names).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Catalog {
    textures: Vec<String>,
    sprite_sets: Vec<String>,
    /// Width and height of each set's images (all the same size), where known.
    sprite_sizes: Vec<Option<(u16, u16)>>,
    /// Animation frames and rotations of each set, where known.
    sprite_frames: Vec<Option<(u8, u8)>>,
    has_sky: bool,
}

impl Catalog {
    /// A catalog of texture and sprite set names (sorted and deduplicated here), and whether a
    /// sky panorama exists.
    pub fn new<T: Into<String>, S: Into<String>>(
        textures: impl IntoIterator<Item = T>,
        sprite_sets: impl IntoIterator<Item = S>,
        has_sky: bool,
    ) -> Catalog {
        let mut textures: Vec<String> = textures.into_iter().map(Into::into).collect();
        let mut sprite_sets: Vec<String> = sprite_sets.into_iter().map(Into::into).collect();
        textures.sort();
        textures.dedup();
        sprite_sets.sort();
        sprite_sets.dedup();
        Catalog {
            textures,
            sprite_sizes: vec![None; sprite_sets.len()],
            sprite_frames: vec![None; sprite_sets.len()],
            sprite_sets,
            has_sky,
        }
    }

    /// The catalog with the size of the images of sprite set `name` known (`width` × `height`
    /// texels), for the checks of things that use it. A name not in the catalog is ignored.
    pub fn with_sprite_size(mut self, name: &str, width: u16, height: u16) -> Catalog {
        if let Ok(index) = self.sprite_sets.binary_search_by(|s| s.as_str().cmp(name)) {
            self.sprite_sizes[index] = Some((width, height));
        }
        self
    }

    /// The catalog with the shape of sprite set `name` known: `frames` animation frames, each
    /// seen from `rotations` directions (1 or 8). A portal's middle (`mid=`) must name a set of
    /// one frame and one rotation. A name not in the catalog is ignored.
    pub fn with_sprite_frames(mut self, name: &str, frames: u8, rotations: u8) -> Catalog {
        if let Ok(index) = self.sprite_sets.binary_search_by(|s| s.as_str().cmp(name)) {
            self.sprite_frames[index] = Some((frames, rotations));
        }
        self
    }

    /// The size given for the images of the sprite set at `index`, if any.
    pub(crate) fn sprite_size(&self, index: u16) -> Option<(u16, u16)> {
        self.sprite_sizes.get(usize::from(index)).copied().flatten()
    }

    /// Texture names, sorted.
    pub fn textures(&self) -> &[String] {
        &self.textures
    }

    /// Sprite set names, sorted; things index this list.
    pub fn sprite_sets(&self) -> &[String] {
        &self.sprite_sets
    }

    /// Whether a sky panorama exists.
    pub fn has_sky(&self) -> bool {
        self.has_sky
    }

    fn texture(&self, name: &Spanned<String>, errors: &mut Vec<Located>) -> u16 {
        lookup(&self.textures, name, "texture", "textures", errors)
    }

    fn sprite(&self, name: &Spanned<String>, errors: &mut Vec<Located>) -> u16 {
        lookup(&self.sprite_sets, name, "sprite", "sprites", errors)
    }

    /// Frames and rotations of the sprite set at `index`, where known.
    fn sprite_frames(&self, index: u16) -> Option<(u8, u8)> {
        self.sprite_frames
            .get(usize::from(index))
            .copied()
            .flatten()
    }
}

fn lookup(
    names: &[String],
    name: &Spanned<String>,
    what: &str,
    folder: &str,
    errors: &mut Vec<Located>,
) -> u16 {
    match names.binary_search(&name.value) {
        Ok(index) => u16::try_from(index).unwrap_or(NO_TEXTURE),
        Err(_) => {
            let known = if names.is_empty() {
                format!("there are none in {folder}/")
            } else {
                let mut list = names
                    .iter()
                    .take(12)
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(", ");
                if names.len() > 12 {
                    list.push_str(", ...");
                }
                format!("known: {list}")
            };
            errors.push((
                name.loc,
                format!(
                    "unknown {what} '{}'; add {folder}/{}.png or use a known one ({known})",
                    name.value, name.value
                ),
            ));
            NO_TEXTURE
        }
    }
}

/// One compiled map, owning its tables (host side); [`CompiledMap::tables`] borrows them in the
/// ROM's layout.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CompiledMap {
    /// File name without extension.
    pub name: String,
    /// Vertices (only those some wall uses).
    pub vertices: Vec<Vertex>,
    /// Walls, grouped by sector, clockwise.
    pub walls: Vec<Wall>,
    /// Sectors, in file order (grid maps: in order of their top-left cells).
    pub sectors: Vec<Sector>,
    /// Things, grouped by sector in sector order.
    pub things: Vec<Thing>,
    /// [`MapTables::sector_things`].
    pub sector_things: Vec<u16>,
    /// [`MapTables::movers`].
    pub movers: Vec<Mover>,
    /// [`MapTables::triggers`].
    pub triggers: Vec<Trigger>,
    /// [`MapTables::lights`].
    pub lights: Vec<Light>,
    /// [`MapTables::wall_twins`].
    pub wall_twins: Vec<u16>,
    /// [`MapTables::slopes`].
    pub slopes: Vec<SectorSlope>,
    /// [`MapTables::layer_links`].
    pub layer_links: Vec<LayerLink>,
    /// Player start.
    pub player_start: PlayerStart,
}

impl CompiledMap {
    /// The tables, as the ROM sees them.
    pub fn tables(&self) -> MapTables<'_> {
        MapTables {
            name: &self.name,
            vertices: &self.vertices,
            walls: &self.walls,
            sectors: &self.sectors,
            player_start: self.player_start,
            things: &self.things,
            sector_things: &self.sector_things,
            movers: &self.movers,
            triggers: &self.triggers,
            lights: &self.lights,
            wall_twins: &self.wall_twins,
            slopes: &self.slopes,
            layer_links: &self.layer_links,
        }
    }
}

/// A sector's walls after the outline checks, clockwise.
struct Outline<'s> {
    walls: Vec<OrientedWall<'s>>,
}

struct OrientedWall<'s> {
    start: usize,
    end: usize,
    source: &'s SourceWall,
}

/// A texture a map uses as a floor or ceiling, and where: the images are checked against this
/// use once they are loaded ([`crate::compile_dir`]), because the span kernels need a square
/// flat while a wall may be any power-of-two rectangle.
#[derive(Clone, Debug)]
pub(crate) struct FlatUse {
    /// Index in the catalog's texture list.
    pub texture: u16,
    /// Where the map names it.
    pub loc: Loc,
    /// "floor" or "ceiling".
    pub what: &'static str,
}

/// What the checks of a thing against its sprite's size need to know ([`finish_things`]): a
/// thing's footprint and height are checked once the sprite's width and height are known, which
/// in an asset directory is after the maps, when the images used are loaded.
#[derive(Clone, Debug)]
pub(crate) struct ThingFit {
    /// The thing's place in the file.
    loc: Loc,
    /// How messages name it: "thing 'torch' at (400, 128)".
    label: String,
    /// The `radius=` written, if any.
    radius: Option<Spanned<i64>>,
    z: i64,
    hanging: bool,
    /// Its sector's floor and ceiling heights: the floor at its highest where the sector is a
    /// lift or a platform (the least room the sprite gets).
    floor: i64,
    ceil: i64,
    /// How messages name the floor: "the floor", or "the platform's floor at its highest".
    floor_name: &'static str,
    /// The lines of its sector's walls, as seen from the thing.
    walls: Vec<WallLine>,
}

/// A wall's line as seen from a point strictly inside its (convex) sector.
#[derive(Clone, Debug)]
struct WallLine {
    /// `65536 · length · distance`: the cross product of the wall, scaled to 24.8, with the point
    /// in 24.8 (positive: the point is on the inner side).
    depth: i128,
    /// The wall's squared length, in square world units.
    length_squared: i128,
    /// How far the sector reaches from the line (to its farthest corner), in world units.
    across: f64,
    /// How messages name it.
    name: String,
}

impl WallLine {
    /// Whether the point is at least `radius` units from the line (exact).
    fn clears(&self, radius: i64) -> bool {
        let reach = 65536 * i128::from(radius);
        self.depth >= 0 && self.depth * self.depth >= reach * reach * self.length_squared
    }

    /// The point's distance from the line, in world units.
    fn distance(&self) -> f64 {
        self.depth as f64 / (65536.0 * (self.length_squared as f64).sqrt())
    }
}

/// Checks `source` and builds its tables. Texture and sprite indices refer to `catalog`. Also
/// returns every use of a texture as a floor or ceiling, with its place in the file, and what
/// [`finish_things`] needs to check each thing of the tables against its sprite's size (the
/// tables' radii are the ones written, or 0, until then).
pub(crate) fn build(
    name: &str,
    source: &SourceMap,
    catalog: &Catalog,
) -> Result<(CompiledMap, Vec<FlatUse>, Vec<ThingFit>), Vec<Located>> {
    let mut errors = Vec::new();
    check_values(source, catalog, &mut errors);
    if source.sectors.is_empty() {
        // Said so, rather than "the player start is in no sector".
        errors.push((
            Loc::START,
            "the map has no sectors; add at least one `sector` line followed by its walls (docs/MAP_FORMAT.md)".to_string(),
        ));
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let outlines: Vec<Option<Outline<'_>>> = source
        .sectors
        .iter()
        .map(|sector| check_outline(source, sector, &mut errors))
        .collect();
    if !errors.is_empty() {
        return Err(errors);
    }
    let outlines: Vec<Outline<'_>> = outlines.into_iter().flatten().collect();
    // Sloped sectors take their lowest floor and highest ceiling as their heights from here on.
    let sloped;
    let (source, slopes) = match resolve_slopes(source, &outlines, &mut errors) {
        Some((resolved, slopes)) => {
            sloped = resolved;
            (&sloped, slopes)
        }
        None => (source, vec![None; source.sectors.len()]),
    };
    if !errors.is_empty() {
        return Err(errors);
    }
    check_portals(source, &outlines, &slopes, &mut errors);
    if errors.is_empty() {
        check_overlaps(source, &outlines, &mut errors);
    }
    let layer_links = if errors.is_empty() {
        let corners: Vec<Vec<Point>> = outlines.iter().map(|o| corners_of(source, o)).collect();
        let sloped: Vec<(bool, bool)> = source
            .sectors
            .iter()
            .map(|s| (s.floor_slope.is_some(), s.ceil_slope.is_some()))
            .collect();
        crate::layers::check_links(source, &corners, &sloped, &mut errors)
    } else {
        Vec::new()
    };
    let middles = if errors.is_empty() {
        pair_middles(source, &outlines, &mut errors)
    } else {
        Vec::new()
    };
    if !errors.is_empty() {
        return Err(errors);
    }
    let player_sector = locate(
        source,
        &outlines,
        &source.player,
        "player start",
        &mut errors,
    );
    if player_sector != NO_PORTAL {
        check_not_in_closing_sector(
            source,
            usize::from(player_sector),
            &source.player,
            "player start",
            &mut errors,
        );
        check_start_clearance(source, &outlines, &source.player, &mut errors);
        check_portal_depth(
            source,
            &outlines,
            &layer_links,
            usize::from(player_sector),
            &mut errors,
        );
    }
    let thing_sectors: Vec<u16> = source
        .things
        .iter()
        .map(|thing| {
            let what = format!("thing '{}'", thing.sprite.value);
            let sector = locate(source, &outlines, &thing.place, &what, &mut errors);
            if sector != NO_PORTAL {
                let sector = usize::from(sector);
                check_not_in_closing_sector(source, sector, &thing.place, &what, &mut errors);
                if layer_links.get(sector).is_some_and(|link| link.below != NO_LINK) {
                    errors.push((
                        thing.place.loc,
                        format!(
                            "{what} stands in {}, whose floor is a portal to the layer below; put it in a sector with a solid floor",
                            source.sectors[sector].label
                        ),
                    ));
                }
                if slopes[sector].is_some() {
                    errors.push((
                        thing.place.loc,
                        format!(
                            "{what} stands in {}, which slopes; things on slopes are not supported yet, so move it to a sector with a flat floor and ceiling",
                            source.sectors[sector].label
                        ),
                    ));
                }
            }
            sector
        })
        .collect();
    if !errors.is_empty() {
        return Err(errors);
    }
    let fits = source
        .things
        .iter()
        .zip(&thing_sectors)
        .map(|(thing, &sector)| thing_fit(source, &outlines, thing, usize::from(sector)))
        .collect();
    let (map, fits) = tables(
        name,
        source,
        catalog,
        &outlines,
        &middles,
        player_sector,
        &thing_sectors,
        fits,
        &slopes,
        layer_links,
    );
    Ok((map, flat_uses(source, catalog), fits))
}

/// The planes of every sector with a slope ([`crate::slopes::resolve`]), and a copy of `source`
/// whose sloped sectors have their lowest floor and highest ceiling as their heights; `None`
/// when no sector slopes (and then nothing is reported). A portal middle on a portal of a
/// sector with a sloped ceiling is refused: its top is the lower ceiling's height.
fn resolve_slopes(
    source: &SourceMap,
    outlines: &[Outline<'_>],
    errors: &mut Vec<Located>,
) -> Option<(SourceMap, Vec<Option<SectorSlope>>)> {
    if source
        .sectors
        .iter()
        .all(|sector| sector.floor_slope.is_none() && sector.ceil_slope.is_none())
    {
        return None;
    }
    let mut resolved = source.clone();
    let slopes: Vec<Option<SectorSlope>> = resolved
        .sectors
        .iter_mut()
        .zip(outlines)
        .map(|(sector, outline)| {
            let corners: Vec<usize> = outline.walls.iter().map(|wall| wall.start).collect();
            crate::slopes::resolve(source, sector, &corners, source.player_size, errors)
        })
        .collect();
    let ceiling_slopes = |sector: usize| source.sectors[sector].ceil_slope.is_some();
    for (index, sector) in source.sectors.iter().enumerate() {
        for wall in &sector.walls {
            let (Some(middle), Some(portal)) = (&wall.middle, &wall.portal) else {
                continue;
            };
            if ceiling_slopes(index) || ceiling_slopes(portal.value) {
                errors.push((
                    middle.loc,
                    "a portal middle (mid=) hangs from the lower of the two ceilings, which a sloped ceiling does not give as one height; make both sectors' ceilings flat, or remove mid=".to_string(),
                ));
            }
        }
    }
    Some((resolved, slopes))
}

/// What [`finish_things`] needs of `thing`, which stands strictly inside sector `sector`.
fn thing_fit(
    source: &SourceMap,
    outlines: &[Outline<'_>],
    thing: &SourceThing,
    sector: usize,
) -> ThingFit {
    let p = (thing.place.x_fx8.value, thing.place.y_fx8.value);
    let label = |vertex: usize| source.vertices[vertex].label.as_str();
    let corners: Vec<Point> = outlines[sector]
        .walls
        .iter()
        .map(|wall| point(source, wall.start))
        .collect();
    let walls = outlines[sector]
        .walls
        .iter()
        .map(|wall| {
            let (a, b) = (point(source, wall.start), point(source, wall.end));
            let (dx, dy) = (i128::from(b.0 - a.0), i128::from(b.1 - a.1));
            let length = ((dx * dx + dy * dy) as f64).sqrt();
            let across = corners
                .iter()
                .map(|&c| cross(a, b, c) as f64 / length)
                .fold(0.0, f64::max);
            let kind = if wall.source.portal.is_some() {
                "portal"
            } else {
                "wall"
            };
            WallLine {
                depth: cross((a.0 * 256, a.1 * 256), (b.0 * 256, b.1 * 256), p),
                length_squared: dx * dx + dy * dy,
                across,
                name: format!(
                    "the {kind} from {} to {} (line {})",
                    label(wall.start),
                    label(wall.end),
                    wall.source.loc.line
                ),
            }
        })
        .collect();
    let sector = &source.sectors[sector];
    // A lift's highest floor is the one drawn; a platform's may be higher.
    let (floor, floor_name) = match mover_range(sector) {
        Some((kind, _, high)) if !kind.moves_ceiling() && high > sector.floor.value => {
            (high, "the platform's floor at its highest")
        }
        _ => (sector.floor.value, "the floor"),
    };
    ThingFit {
        loc: thing.place.loc,
        label: format!(
            "thing '{}' at ({}, {})",
            thing.sprite.value,
            fx8(p.0),
            fx8(p.1)
        ),
        radius: thing.options.radius.clone(),
        z: thing.options.z,
        hanging: thing.options.hanging,
        floor,
        ceil: sector.ceil.value,
        floor_name,
        walls,
    }
}

/// Checks each thing of `map` against its sprite's size and sets its footprint radius: the
/// `radius=` written, at least half the sprite's width rounded up (the default), and the disc
/// of that radius must lie inside the thing's sector; the sprite must fit between the sector's
/// floor and ceiling. `fits` are [`build`]'s, in the order of `map.things`; `size` gives the
/// width and height of a sprite set's images (all the same size) by its index in `map`, or
/// `None` to skip the checks (an image that did not load, already reported). Returns the
/// errors, each at the thing's place.
pub(crate) fn finish_things(
    map: &mut CompiledMap,
    fits: &[ThingFit],
    size: impl Fn(u16) -> Option<(u16, u16)>,
) -> Vec<Located> {
    let mut errors = Vec::new();
    for (thing, fit) in map.things.iter_mut().zip(fits) {
        let written = fit.radius.as_ref().map(|r| r.value);
        thing.radius = written.unwrap_or(0) as u16;
        let Some((width, height)) = size(thing.sprite) else {
            continue;
        };
        let least = i64::from(width.div_ceil(2));
        let radius = match &fit.radius {
            Some(r) if r.value < least => {
                errors.push((
                    r.loc,
                    format!(
                        "radius={} is less than half the width of the sprite ({width}); use radius={least} or more, or leave radius= out (the default is {least})",
                        r.value
                    ),
                ));
                least
            }
            Some(r) => r.value,
            None => least,
        };
        thing.radius = radius as u16;
        check_footprint(fit, radius, least, &mut errors);
        check_thing_height(fit, i64::from(height), &mut errors);
    }
    errors
}

/// The places of `map`'s things whose sprite (its size by `size`) [`finish_things`] would
/// refuse: a footprint crossing a wall's line of its sector, or a sprite through its floor or
/// ceiling. The Doom importer leaves those things out.
pub(crate) fn misfits(
    map: &CompiledMap,
    fits: &[ThingFit],
    size: impl Fn(u16) -> Option<(u16, u16)>,
) -> Vec<Loc> {
    map.things
        .iter()
        .zip(fits)
        .filter(|(thing, fit)| {
            let Some((width, height)) = size(thing.sprite) else {
                return false;
            };
            let least = i64::from(width.div_ceil(2));
            let radius = fit.radius.as_ref().map_or(least, |r| r.value.max(least));
            let mut errors = Vec::new();
            check_footprint(fit, radius, least, &mut errors);
            check_thing_height(fit, i64::from(height), &mut errors);
            !errors.is_empty()
        })
        .map(|(_, fit)| fit.loc)
        .collect()
}

/// Refuses a thing whose footprint disc crosses the line of a wall of its sector, naming the
/// wall it crosses most.
fn check_footprint(fit: &ThingFit, radius: i64, least: i64, errors: &mut Vec<Located>) {
    let Some(wall) = fit
        .walls
        .iter()
        .filter(|wall| !wall.clears(radius))
        .min_by(|a, b| a.distance().total_cmp(&b.distance()))
    else {
        return;
    };
    let smaller = fit.radius.is_some() && radius > least;
    let advice = if wall.across >= 2.0 * radius as f64 {
        // Rounded up to a 256th, the positions' resolution, so moving that far is enough.
        let short = ((radius as f64 - wall.distance()) * 256.0).ceil().max(1.0) as i64;
        let smaller = if smaller {
            format!(", or give a smaller radius= (down to {least})")
        } else {
            String::new()
        };
        format!(
            "move the thing at least {} further from that wall{smaller}",
            fx8(short)
        )
    } else {
        let fix = if smaller {
            format!("give a smaller radius= (down to {least}) or widen the sector")
        } else {
            "widen the sector or use a narrower sprite".to_string()
        };
        format!(
            "the sector is only {} across from that wall, less than the footprint's {}: {fix}",
            fx8((wall.across * 256.0).floor() as i64),
            2 * radius
        )
    };
    errors.push((
        fit.loc,
        format!(
            "{}: its footprint (radius {radius}) crosses the line of {} of its sector, {} from its centre; {advice} (a thing's footprint must lie inside its sector)",
            fit.label,
            wall.name,
            fx8((wall.distance() * 256.0).floor() as i64),
        ),
    ));
}

/// Refuses a thing whose sprite (`height` tall) pokes through its sector's ceiling or floor.
fn check_thing_height(fit: &ThingFit, height: i64, errors: &mut Vec<Located>) {
    let room = fit.ceil - fit.floor;
    let (z, label, floor_name) = (fit.z, &fit.label, fit.floor_name);
    // How far the sprite passes the floor (hanging) or the ceiling (standing), and the words
    // that say where it is.
    let (over, placed) = if fit.hanging {
        let bottom = fit.ceil - z - height;
        (
            fit.floor - bottom,
            format!(
                "hangs {z} below the ceiling ({}), so its bottom ({bottom}) is {} below {floor_name} ({})",
                fit.ceil,
                fit.floor - bottom,
                fit.floor
            ),
        )
    } else {
        let top = fit.floor + z + height;
        (
            top - fit.ceil,
            format!(
                "stands {z} above {floor_name} ({}), so its top ({top}) is {} above the ceiling ({})",
                fit.floor,
                top - fit.ceil,
                fit.ceil
            ),
        )
    };
    let message = (over > 0).then(|| {
        let fix = if z >= over {
            format!("lower z= by {over} (to {})", z - over)
        } else if floor_name == "the floor" {
            format!("its sector is only {room} tall: raise the ceiling or use a shorter sprite")
        } else {
            format!("only {room} lies between {floor_name} and the ceiling: raise the ceiling, lower the platform's top or use a shorter sprite")
        };
        format!("{label}: the sprite is {height} tall and {placed}; {fix}")
    });
    errors.extend(message.map(|m| (fit.loc, m)));
}

/// Checks a wall's middle words as written on its line: `mid=` names a still sprite set, and
/// `mid=`, `blocks` and `translucent` go on portals only, the last two with `mid=`.
fn check_middle_words(wall: &SourceWall, catalog: &Catalog, errors: &mut Vec<Located>) {
    if let Some(name) = &wall.middle {
        let index = catalog.sprite(name, errors);
        match catalog.sprite_frames(index) {
            Some((frames, rotations)) if frames > 1 || rotations > 1 => {
                let shape = match (frames > 1, rotations > 1) {
                    (true, true) => format!("{frames} frames in {rotations} rotations"),
                    (true, false) => format!("{frames} animation frames"),
                    _ => format!("{rotations} rotations"),
                };
                errors.push((
                    name.loc,
                    format!(
                        "mid= needs a still image, but sprite set '{}' has {shape}; use a set of one image (sprites/NAME.png)",
                        name.value
                    ),
                ));
            }
            _ => {}
        }
    }
    if wall.portal.is_none() {
        if let Some(name) = &wall.middle {
            errors.push((
                name.loc,
                "a masked texture on a solid wall: mid= is the image drawn in a portal's opening; remove mid=, or make the wall a portal=SECTOR".to_string(),
            ));
        }
        if let Some(at) = wall.blocks {
            errors.push((
                at,
                "'blocks' applies to portals only (a solid wall always blocks); remove it"
                    .to_string(),
            ));
        }
        if let Some(at) = wall.translucent {
            errors.push((
                at,
                "'translucent' applies to a portal's middle image only; remove it (and use mid= on a portal)".to_string(),
            ));
        }
        return;
    }
    if wall.middle.is_none() {
        if let Some(at) = wall.blocks {
            errors.push((
                at,
                "'blocks' needs mid= on the same line: a portal the player cannot pass shows what stops it; add mid=SPRITE (a grate, bars), or remove blocks".to_string(),
            ));
        }
        if let Some(at) = wall.translucent {
            errors.push((
                at,
                "'translucent' needs mid= on the same line: it draws the portal's middle image at 50 %; add mid=SPRITE, or remove translucent".to_string(),
            ));
        }
    }
}

/// A portal's middle as one side's line gives it: the set's name, `blocks`, `translucent`.
fn middle_words(wall: &SourceWall) -> Option<(&str, bool, bool)> {
    wall.middle.as_ref().map(|name| {
        (
            name.value.as_str(),
            wall.blocks.is_some(),
            wall.translucent.is_some(),
        )
    })
}

/// The middle of each portal, shared by its two sides: per sector (outline order), per wall, the
/// source wall whose line describes it, if either does. A portal's middle is one object seen
/// from both sides, so a side that gives no `mid=` takes the other side's `mid=`, `blocks` and
/// `translucent`; two sides that both give `mid=` must give the same three (else an error at
/// the later line). Runs once the portals pair up ([`check_portals`]).
fn pair_middles<'s>(
    source: &SourceMap,
    outlines: &[Outline<'s>],
    errors: &mut Vec<Located>,
) -> Vec<Vec<Option<&'s SourceWall>>> {
    let mut by_edge: HashMap<(usize, usize), &'s SourceWall> = HashMap::new();
    for wall in outlines.iter().flat_map(|o| &o.walls) {
        by_edge.insert((wall.start, wall.end), wall.source);
    }
    let label = |vertex: usize| source.vertices[vertex].label.as_str();
    outlines
        .iter()
        .map(|outline| {
            outline
                .walls
                .iter()
                .map(|wall| {
                    wall.source.portal.as_ref()?;
                    let back = by_edge.get(&(wall.end, wall.start)).copied();
                    let here = middle_words(wall.source);
                    let there = back.and_then(middle_words);
                    match (here, there, back) {
                        (Some(a), Some(b), Some(back)) if a != b => {
                            // Reported once, at the later of the two lines.
                            if back.loc.line < wall.source.loc.line {
                                let describe = |(name, blocks, translucent): (&str, bool, bool)| {
                                    let mut words = format!("mid={name}");
                                    if blocks {
                                        words.push_str(" blocks");
                                    }
                                    if translucent {
                                        words.push_str(" translucent");
                                    }
                                    words
                                };
                                let at = wall.source.middle.as_ref().map_or(wall.source.loc, |m| m.loc);
                                errors.push((
                                    at,
                                    format!(
                                        "this side of the portal from {} to {} gives `{}`, the other side (line {}) `{}`; a portal's middle is one image seen from both sides: give it on one side only (the other side gets it), or the same on both",
                                        label(wall.start),
                                        label(wall.end),
                                        describe(a),
                                        back.loc.line,
                                        describe(b)
                                    ),
                                ));
                            }
                            Some(wall.source)
                        }
                        (Some(_), _, _) => Some(wall.source),
                        (None, Some(_), back) => back,
                        (None, None, _) => None,
                    }
                })
                .collect()
        })
        .collect()
}

/// Every floor and ceiling texture of the map with the place that names it (a grid's sectors of
/// one kind share their legend line's place; the caller's sorted diagnostics drop repeats).
fn flat_uses(source: &SourceMap, catalog: &Catalog) -> Vec<FlatUse> {
    let mut ignore = Vec::new();
    let mut uses = Vec::new();
    for sector in &source.sectors {
        let ceiling = match &sector.ceiling {
            CeilingSource::Texture(name) => Some(("ceiling", name)),
            CeilingSource::Sky => None,
        };
        for (what, name) in std::iter::once(("floor", &sector.floor_texture)).chain(ceiling) {
            uses.push(FlatUse {
                texture: catalog.texture(name, &mut ignore),
                loc: name.loc,
                what,
            });
        }
    }
    uses
}

fn point(source: &SourceMap, vertex: usize) -> Point {
    let v = &source.vertices[vertex];
    (v.x.value, v.y.value)
}

/// The corners of `outline`, clockwise.
fn corners_of(source: &SourceMap, outline: &Outline<'_>) -> Vec<Point> {
    outline
        .walls
        .iter()
        .map(|wall| point(source, wall.start))
        .collect()
}

fn check_values(source: &SourceMap, catalog: &Catalog, errors: &mut Vec<Located>) {
    let limit = i64::from(WORLD_COORD_MAX);
    let mut positions: HashMap<Point, usize> = HashMap::new();
    for (index, vertex) in source.vertices.iter().enumerate() {
        for (axis, value) in [("x", &vertex.x), ("y", &vertex.y)] {
            if value.value.abs() > limit {
                errors.push((
                    value.loc,
                    format!(
                        "{} {axis} {} is outside the map limits; keep coordinates within -{limit}..={limit}",
                        vertex.label, value.value
                    ),
                ));
            }
        }
        let at = (vertex.x.value, vertex.y.value);
        if let Some(&first) = positions.get(&at) {
            let first = &source.vertices[first];
            errors.push((
                vertex.x.loc,
                format!(
                    "{} is at ({}, {}) like {}; use {} instead of a second vertex at the same place",
                    vertex.label, at.0, at.1, first.label, first.label
                ),
            ));
        } else {
            positions.insert(at, index);
        }
    }
    let count_limit = |what: &str, count: usize, max: usize, errors: &mut Vec<Located>| {
        if count > max {
            errors.push((
                Loc::START,
                format!("the map has {count} {what}, more than the tables can index ({max}); split the map"),
            ));
        }
    };
    count_limit(
        "vertices",
        source.vertices.len(),
        usize::from(u16::MAX),
        errors,
    );
    // Sector ids stop below NO_PORTAL.
    count_limit(
        "sectors",
        source.sectors.len(),
        usize::from(NO_PORTAL),
        errors,
    );
    let wall_total: usize = source.sectors.iter().map(|s| s.walls.len()).sum();
    count_limit("walls", wall_total, usize::from(u16::MAX), errors);

    // The tags of the map's movers and switched lights, which every switch and line must name
    // one of.
    let mut target_tags: Vec<u16> = source
        .sectors
        .iter()
        .flat_map(|sector| {
            let mover = sector.mover.as_ref().and_then(|m| m.tag.as_ref());
            let light = sector.light_effect.as_ref().and_then(|l| l.tag.as_ref());
            mover.into_iter().chain(light).map(|tag| tag.value)
        })
        .collect();
    target_tags.sort_unstable();
    target_tags.dedup();
    for (index, sector) in source.sectors.iter().enumerate() {
        check_sector_values(source, index, sector, catalog, &target_tags, errors);
    }
    if let Some(extra) = source
        .sectors
        .iter()
        .filter_map(|sector| sector.mover.as_ref())
        .nth(MOVERS_MAX as usize)
    {
        let count = source.sectors.iter().filter(|s| s.mover.is_some()).count();
        errors.push((
            extra.loc,
            format!(
                "the map has {count} movers, more than the {MOVERS_MAX} a map may hold (this is the first beyond); remove some or split the map"
            ),
        ));
    }
    if let Some(extra) = source
        .sectors
        .iter()
        .filter_map(|sector| sector.light_effect.as_ref())
        .nth(LIGHTS_MAX as usize)
    {
        let count = source
            .sectors
            .iter()
            .filter(|s| s.light_effect.is_some())
            .count();
        errors.push((
            extra.low.loc,
            format!(
                "the map has {count} light effects, more than the {LIGHTS_MAX} a map may hold (this is the first beyond); remove some or split the map"
            ),
        ));
    }
    let trigger_words: Vec<Loc> = source
        .sectors
        .iter()
        .flat_map(|sector| &sector.walls)
        .filter_map(|wall| {
            let switch = wall.switch.as_ref().map(|s| s.loc);
            switch.or(wall.trigger.as_ref().map(|t| t.loc))
        })
        .collect();
    if let Some(&extra) = trigger_words.get(TRIGGERS_MAX as usize) {
        errors.push((
            extra,
            format!(
                "the map has {} switches and walk-over lines, more than the {TRIGGERS_MAX} a map may hold (this is the first beyond); remove some or split the map",
                trigger_words.len()
            ),
        ));
    }
    for place in std::iter::once(&source.player).chain(source.things.iter().map(|t| &t.place)) {
        for (axis, value) in [("x", &place.x_fx8), ("y", &place.y_fx8)] {
            if value.value.abs() > limit * 256 {
                errors.push((
                    value.loc,
                    format!(
                        "{axis} {} is outside the map limits; keep positions within -{limit}..={limit}",
                        fx8(value.value)
                    ),
                ));
            }
        }
    }
    for thing in &source.things {
        catalog.sprite(&thing.sprite, errors);
    }
    if let Some(extra) = source.things.get(THINGS_MAX as usize) {
        errors.push((
            extra.place.loc,
            format!(
                "the map has {} things, more than the {THINGS_MAX} a map may hold (this is the first beyond); remove some or split the map",
                source.things.len()
            ),
        ));
    }
}

/// The heights a sector's mover moves its plane between, `(low, high)` ([`Mover::low`],
/// [`Mover::high`]), from the heights drawn and the mover's word; `None` for a sector that does
/// not move.
fn mover_range(sector: &SourceSector) -> Option<(MoverKind, i64, i64)> {
    let mover = sector.mover.as_ref()?;
    let (floor, ceil) = (sector.floor.value, sector.ceil.value);
    let other = mover.height.as_ref().map_or(floor, |h| h.value);
    Some(match mover.kind {
        MoverKind::Door => (MoverKind::Door, floor, ceil),
        MoverKind::Lift => (MoverKind::Lift, other, floor),
        MoverKind::Platform => (MoverKind::Platform, other.min(floor), other.max(floor)),
        MoverKind::Crusher => (MoverKind::Crusher, other, ceil),
    })
}

/// The lowest and highest heights a sector's floor and its ceiling take as its mover moves:
/// `((floor low, floor high), (ceiling low, ceiling high))`.
pub(crate) fn plane_spans(sector: &SourceSector) -> ((i64, i64), (i64, i64)) {
    let (floor, ceil) = (sector.floor.value, sector.ceil.value);
    match mover_range(sector) {
        Some((kind, low, high)) if kind.moves_ceiling() => ((floor, floor), (low, high)),
        Some((_, low, high)) => ((low, high), (ceil, ceil)),
        None => ((floor, floor), (ceil, ceil)),
    }
}

/// Checks the height a mover word gives against the limits and the sector's floor and ceiling:
/// a lift goes down below the floor, a platform's other end is not the floor and stays below
/// the ceiling, a crusher's ceiling comes down to a height strictly between floor and ceiling.
fn check_mover_heights(sector: &SourceSector, mover: &SourceMover, errors: &mut Vec<Located>) {
    let Some(height) = &mover.height else {
        return;
    };
    let (value, name) = (height.value, mover.kind.name());
    if !(i64::from(HEIGHT_MIN)..=i64::from(HEIGHT_MAX)).contains(&value) {
        errors.push((
            height.loc,
            format!("{name} height {value} is outside the limits; use {HEIGHT_MIN}..={HEIGHT_MAX}"),
        ));
        return;
    }
    let (floor, ceil) = (sector.floor.value, sector.ceil.value);
    let problem = match mover.kind {
        MoverKind::Lift if value >= floor => Some(format!(
            "lift={value} is not below the sector's floor ({floor}): a lift's floor goes down from the floor drawn to LOW and back; use a LOW under {floor} (draw the sector at its raised height)"
        )),
        MoverKind::Platform if value == floor => Some(format!(
            "platform={value} is the sector's own floor, so the platform would not move; give the other height its floor moves to"
        )),
        MoverKind::Platform if value >= ceil => Some(format!(
            "platform={value} is not below the sector's ceiling ({ceil}): the floor would rise into it; use a height under {ceil}"
        )),
        MoverKind::Crusher if value <= floor || value >= ceil => Some(format!(
            "crusher={value} is not between the sector's floor ({floor}) and ceiling ({ceil}): a crusher's ceiling comes down from the ceiling drawn to LOW and back; use a LOW strictly between them"
        )),
        _ => None,
    };
    errors.extend(problem.map(|message| (height.loc, message)));
}

/// Checks a wall's trigger words as written on its line: `switch=TEX tag=N` on a solid wall,
/// `trigger=N` on a portal, and the tag of each names some mover or switched light of the map
/// (`target_tags`, sorted): a trigger that starts nothing is a mistake in the map.
fn check_trigger_words(
    wall: &SourceWall,
    catalog: &Catalog,
    target_tags: &[u16],
    errors: &mut Vec<Located>,
) {
    let mut tag = None;
    if let Some(texture) = &wall.switch {
        catalog.texture(texture, errors);
        if wall.portal.is_some() {
            errors.push((
                texture.loc,
                "switch= goes on a solid wall (the player uses it, facing it); on a portal write trigger=N: crossing the line starts the movers tagged N".to_string(),
            ));
        } else if wall.tag.is_none() {
            errors.push((
                texture.loc,
                "switch= needs tag=N on the same line: using the switch starts the movers with tag=N; add tag=N".to_string(),
            ));
        } else {
            tag = wall.tag.as_ref();
        }
    } else if let Some(written) = &wall.tag {
        errors.push((
            written.loc,
            "tag= on a wall goes with switch=TEX (a switch starts the movers of its tag); add switch=TEX, or on a portal the player walks over write trigger=N instead".to_string(),
        ));
    }
    if let Some(trigger) = &wall.trigger {
        if wall.portal.is_none() {
            errors.push((
                trigger.loc,
                "trigger= goes on a portal (crossing it from this side starts the movers of its tag); on a solid wall write switch=TEX tag=N".to_string(),
            ));
        } else {
            tag = Some(trigger);
        }
    }
    if let Some(tag) = tag {
        if target_tags.binary_search(&tag.value).is_err() {
            errors.push((
                tag.loc,
                format!(
                    "no mover or switched light has tag {0}; give a moving sector (door, lift=, platform=, crusher=) or a switched light (switched=LOW) tag={0}, or use the tag of one",
                    tag.value
                ),
            ));
        }
    }
}

fn check_sector_values(
    source: &SourceMap,
    index: usize,
    sector: &SourceSector,
    catalog: &Catalog,
    target_tags: &[u16],
    errors: &mut Vec<Located>,
) {
    for (what, height) in [("floor", &sector.floor), ("ceiling", &sector.ceil)] {
        if !(i64::from(HEIGHT_MIN)..=i64::from(HEIGHT_MAX)).contains(&height.value) {
            errors.push((
                height.loc,
                format!(
                    "{what} height {} is outside the limits; use {HEIGHT_MIN}..={HEIGHT_MAX}",
                    height.value
                ),
            ));
        }
    }
    if sector.floor.value >= sector.ceil.value {
        errors.push((
            sector.ceil.loc,
            format!(
                "{}: floor {} is not below ceiling {}; raise the ceiling or lower the floor",
                sector.label, sector.floor.value, sector.ceil.value
            ),
        ));
    }
    catalog.texture(&sector.floor_texture, errors);
    match &sector.ceiling {
        CeilingSource::Texture(name) => {
            catalog.texture(name, errors);
        }
        CeilingSource::Sky if !catalog.has_sky => errors.push((
            sector.loc,
            format!(
                "{} has a sky ceiling but there is no sky/sky.png; add the panorama or give the ceiling a texture",
                sector.label
            ),
        )),
        CeilingSource::Sky => {}
    }
    if let Some(light) = &sector.light_effect {
        if light.low.value >= sector.light {
            errors.push((
                light.low.loc,
                format!(
                    "{}: {}={} is not below the sector's light {}: the effect goes from light= down to this level; lower it, or raise light=",
                    sector.label, light.word, light.low.value, sector.light
                ),
            ));
        }
    }
    if let Some(mover) = &sector.mover {
        check_mover_heights(sector, mover, errors);
    }
    for wall in &sector.walls {
        for offset in [&wall.x_offset, &wall.y_offset] {
            // Offsets are stored as i16; the renderer reduces them modulo the texture size.
            if offset.value.abs() > i64::from(TEXTURE_COORD_MAX) {
                errors.push((
                    offset.loc,
                    format!(
                        "texture offset {} is out of range; use -{TEXTURE_COORD_MAX}..={TEXTURE_COORD_MAX} (offsets wrap at the texture size anyway)",
                        offset.value
                    ),
                ));
            }
        }
        for texture in [&wall.texture, &wall.upper, &wall.lower]
            .into_iter()
            .flatten()
        {
            catalog.texture(texture, errors);
        }
        check_middle_words(wall, catalog, errors);
        check_trigger_words(wall, catalog, target_tags, errors);
        match &wall.portal {
            Some(portal) => {
                if portal.value == index {
                    errors.push((
                        portal.loc,
                        format!(
                            "{} has a portal to itself; name the sector on the other side",
                            sector.label
                        ),
                    ));
                }
                if let Some(texture) = &wall.texture {
                    errors.push((
                        texture.loc,
                        "a portal has no middle texture; remove tex= (use upper= and lower= for the step strips)".to_string(),
                    ));
                }
            }
            None => {
                if wall.texture.is_none() {
                    errors.push((
                        wall.loc,
                        format!(
                            "solid wall from {} to {} needs tex=TEXTURE (or portal=SECTOR if it opens into a neighbour)",
                            source.vertices[wall.start].label, source.vertices[wall.end].label
                        ),
                    ));
                }
                for strip in [&wall.upper, &wall.lower].into_iter().flatten() {
                    errors.push((
                        strip.loc,
                        "upper= and lower= apply to portals only; use tex= on a solid wall"
                            .to_string(),
                    ));
                }
            }
        }
    }
}

fn check_outline<'s>(
    source: &'s SourceMap,
    sector: &'s SourceSector,
    errors: &mut Vec<Located>,
) -> Option<Outline<'s>> {
    let label = |vertex: usize| source.vertices[vertex].label.as_str();
    let walls = &sector.walls;
    if walls.len() < 3 {
        errors.push((
            sector.loc,
            format!(
                "{} has {} wall{}; a sector needs at least 3 walls forming a closed loop",
                sector.label,
                walls.len(),
                if walls.len() == 1 { "" } else { "s" }
            ),
        ));
        return None;
    }
    let before = errors.len();
    for (i, wall) in walls.iter().enumerate() {
        if wall.start == wall.end {
            errors.push((
                wall.loc,
                format!(
                    "wall from {} to itself has zero length; remove it",
                    label(wall.start)
                ),
            ));
        }
        let next = &walls[(i + 1) % walls.len()];
        if wall.end != next.start {
            let message = if i + 1 == walls.len() {
                format!(
                    "{}: the last wall ends at {} but the first wall starts at {}; close the loop",
                    sector.label,
                    label(wall.end),
                    label(next.start)
                )
            } else {
                format!(
                    "wall starts at {} but the previous wall ends at {}; list walls in order so each starts where the previous one ends",
                    label(next.start),
                    label(wall.end)
                )
            };
            errors.push((
                if i + 1 == walls.len() {
                    wall.loc
                } else {
                    next.loc
                },
                message,
            ));
        }
    }
    if errors.len() > before {
        return None;
    }

    let points: Vec<Point> = walls.iter().map(|w| point(source, w.start)).collect();
    let area = double_area(&points);
    if area == 0 {
        errors.push((
            sector.loc,
            format!(
                "{} has zero area; its vertices must not all lie on one line",
                sector.label
            ),
        ));
        return None;
    }
    // The file may list a sector either way round; the tables store it clockwise.
    let oriented: Vec<OrientedWall<'_>> = if area > 0 {
        walls
            .iter()
            .map(|w| OrientedWall {
                start: w.start,
                end: w.end,
                source: w,
            })
            .collect()
    } else {
        walls
            .iter()
            .rev()
            .map(|w| OrientedWall {
                start: w.end,
                end: w.start,
                source: w,
            })
            .collect()
    };

    let n = oriented.len();
    for i in 0..n {
        let (wall, next) = (&oriented[i], &oriented[(i + 1) % n]);
        let (a, b, c) = (
            point(source, wall.start),
            point(source, wall.end),
            point(source, next.end),
        );
        let turn = cross(a, b, c);
        if turn < 0 {
            errors.push((
                next.source.loc,
                format!(
                    "{} is not convex at {}: its walls turn the other way there; split it into convex sectors joined by portals",
                    sector.label,
                    label(wall.end)
                ),
            ));
        } else if turn == 0 && dot(b, a, c) > 0 {
            errors.push((
                next.source.loc,
                format!(
                    "{} folds back on itself at {}: the walls before and after it overlap; remove the spike",
                    sector.label,
                    label(wall.end)
                ),
            ));
        }
    }
    for i in 0..n {
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let (w, v) = (&oriented[i], &oriented[j]);
            if segments_touch(
                point(source, w.start),
                point(source, w.end),
                point(source, v.start),
                point(source, v.end),
            ) {
                errors.push((
                    v.source.loc,
                    format!(
                        "{}: the wall from {} to {} touches or crosses the wall from {} to {} (line {}); a sector's outline must not meet itself",
                        sector.label,
                        label(v.start),
                        label(v.end),
                        label(w.start),
                        label(w.end),
                        w.source.loc.line
                    ),
                ));
            }
        }
    }
    if errors.len() > before {
        return None;
    }
    Some(Outline { walls: oriented })
}

fn check_portals(
    source: &SourceMap,
    outlines: &[Outline<'_>],
    slopes: &[Option<SectorSlope>],
    errors: &mut Vec<Located>,
) {
    let label = |vertex: usize| source.vertices[vertex].label.as_str();
    // Sectors on different layers may share walls (room over room).
    let mut edges: HashMap<(i64, usize, usize), (usize, &OrientedWall<'_>)> = HashMap::new();
    let mut linked_pairs_reported = std::collections::HashSet::new();
    for (sector_index, outline) in outlines.iter().enumerate() {
        for wall in &outline.walls {
            let layer = source.sectors[sector_index].layer.value;
            if let Some((other, first)) =
                edges.insert((layer, wall.start, wall.end), (sector_index, wall))
            {
                let pair = (sector_index.min(other), sector_index.max(other));
                let is_linked = linked(source, sector_index, other);
                if is_linked && !linked_pairs_reported.insert(pair) {
                    continue;
                }
                let message = if is_linked {
                    format!(
                        "{} and {} (line {}) are linked through a floor or ceiling but both on layer {layer}; give one of them another layer=",
                        source.sectors[sector_index].label,
                        source.sectors[other].label,
                        source.sectors[other].loc.line
                    )
                } else {
                    format!(
                        "the wall from {} to {} is also a wall of {} (line {}) in the same direction; those sectors overlap, fix their outlines (or put them on different layers with layer=, for room over room)",
                        label(wall.start),
                        label(wall.end),
                        source.sectors[other].label,
                        first.source.loc.line
                    )
                };
                errors.push((wall.source.loc, message));
            }
        }
    }
    for (here_index, outline) in outlines.iter().enumerate() {
        let here = &source.sectors[here_index];
        for wall in &outline.walls {
            let Some(portal) = &wall.source.portal else {
                continue;
            };
            let there = &source.sectors[portal.value];
            match edges.get(&(there.layer.value, wall.end, wall.start)) {
                None => errors.push((
                    portal.loc,
                    format!(
                        "portal to {}: it has no wall from {} to {}; add one with portal= back to this sector (both sides of a portal must use the same two vertices: split longer walls at shared vertices)",
                        there.label,
                        label(wall.end),
                        label(wall.start)
                    ),
                )),
                Some(&(owner, _)) if owner != portal.value => errors.push((
                    portal.loc,
                    format!(
                        "portal to {}, but the wall from {} to {} on the other side belongs to {}; point portal= at that sector",
                        there.label,
                        label(wall.end),
                        label(wall.start),
                        source.sectors[owner].label
                    ),
                )),
                Some(&(_, back)) => match &back.source.portal {
                    Some(back_portal) if back_portal.value == here_index => {}
                    Some(back_portal) => errors.push((
                        portal.loc,
                        format!(
                            "portal to {}, but its wall back (line {}) leads to {}; make both sides name each other",
                            there.label,
                            back.source.loc.line,
                            source.sectors[back_portal.value].label
                        ),
                    )),
                    None => errors.push((
                        portal.loc,
                        format!(
                            "portal to {}, but its wall from {} to {} (line {}) is solid; make it a portal back to this sector",
                            there.label,
                            label(wall.end),
                            label(wall.start),
                            back.source.loc.line
                        ),
                    )),
                },
            }
            if slopes[here_index].is_some() || slopes[portal.value].is_some() {
                let planes = |index: usize, sector: &SourceSector| {
                    slopes[index].unwrap_or(SectorSlope {
                        floor: Plane::flat(sector.floor.value as i32),
                        ceiling: Plane::flat(sector.ceil.value as i32),
                    })
                };
                let ends = [wall.start, wall.end].map(|vertex| {
                    let (x, y) = point(source, vertex);
                    (
                        source.vertices[vertex].label.as_str(),
                        (x * 256) as i32,
                        (y * 256) as i32,
                    )
                });
                check_sloped_strips(
                    (here, planes(here_index, here)),
                    (there, planes(portal.value, there)),
                    wall.source,
                    ends,
                    portal.loc,
                    errors,
                );
            } else {
                check_strips(here, there, wall.source, portal.loc, errors);
            }
        }
    }
}

/// [`check_strips`] where either sector slopes (neither moves): the strips show where the
/// heights at either end of the wall `ends` (each a vertex's name and 24.8 position) say so.
fn check_sloped_strips(
    (here, here_planes): (&SourceSector, SectorSlope),
    (there, there_planes): (&SourceSector, SectorSlope),
    wall: &SourceWall,
    ends: [(&str, i32, i32); 2],
    at: Loc,
    errors: &mut Vec<Located>,
) {
    let both_sky =
        matches!(here.ceiling, CeilingSource::Sky) && matches!(there.ceiling, CeilingSource::Sky);
    let units = |fx8: i32| fx8 as f64 / 256.0;
    for (name, x, y) in ends {
        let height = |plane: &Plane| plane.height_fx8_at(x, y);
        let (here_ceil, there_ceil) = (height(&here_planes.ceiling), height(&there_planes.ceiling));
        if wall.upper.is_none() && !both_sky && there_ceil < here_ceil {
            errors.push((
                at,
                format!(
                    "portal to {} needs upper=TEXTURE: at {name} its ceiling ({}) is lower than this sector's ({}), so a strip of wall shows above the opening",
                    there.label,
                    units(there_ceil),
                    units(here_ceil)
                ),
            ));
            break;
        }
    }
    for (name, x, y) in ends {
        let height = |plane: &Plane| plane.height_fx8_at(x, y);
        let (here_floor, there_floor) = (height(&here_planes.floor), height(&there_planes.floor));
        if wall.lower.is_none() && there_floor > here_floor {
            errors.push((
                at,
                format!(
                    "portal to {} needs lower=TEXTURE: at {name} its floor ({}) is higher than this sector's ({}), so a step shows below the opening",
                    there.label,
                    units(there_floor),
                    units(here_floor)
                ),
            ));
            break;
        }
    }
}

/// Refuses a portal from `here` to `there` (written as `wall`, its `portal=` at `at`) that lacks
/// the `upper=` or `lower=` texture of a strip some heights show: the heights drawn, or any the
/// two sectors' movers give their floors and ceilings (the renderer draws nothing where a strip
/// has no texture). An upper strip shows where `there`'s ceiling is below `here`'s (unless both
/// show the sky), a lower strip where `there`'s floor is above `here`'s.
fn check_strips(
    here: &SourceSector,
    there: &SourceSector,
    wall: &SourceWall,
    at: Loc,
    errors: &mut Vec<Located>,
) {
    let both_sky =
        matches!(here.ceiling, CeilingSource::Sky) && matches!(there.ceiling, CeilingSource::Sky);
    let (here_floor, here_ceil) = plane_spans(here);
    let (there_floor, there_ceil) = plane_spans(there);
    let kind_of = |sector: &SourceSector| sector.mover.as_ref().map_or("", |m| m.kind.name());
    if wall.upper.is_none() && !both_sky {
        let message = if there.ceil.value < here.ceil.value {
            Some(format!(
                "its ceiling ({}) is lower than this sector's ({})",
                there.ceil.value, here.ceil.value
            ))
        } else if there_ceil.0 < here.ceil.value {
            let closed = if kind_of(there) == "door" {
                " when it closes"
            } else {
                ""
            };
            Some(format!(
                "it is a {} whose ceiling comes down to {}{closed}, lower than this sector's ({})",
                kind_of(there),
                there_ceil.0,
                here.ceil.value
            ))
        } else if there.ceil.value < here_ceil.1 {
            Some(format!(
                "this sector is a {} whose ceiling rises to {}, higher than the neighbour's ({})",
                kind_of(here),
                here_ceil.1,
                there.ceil.value
            ))
        } else if there_ceil.0 < here_ceil.1 {
            Some(format!(
                "it is a {} whose ceiling comes down to {} and this sector a {} whose ceiling rises to {}",
                kind_of(there),
                there_ceil.0,
                kind_of(here),
                here_ceil.1
            ))
        } else {
            None
        };
        if let Some(why) = message {
            errors.push((
                at,
                format!(
                    "portal to {} needs upper=TEXTURE: {why}, so a strip of wall shows above the opening",
                    there.label
                ),
            ));
        }
    }
    if wall.lower.is_none() {
        let message = if there.floor.value > here.floor.value {
            Some(format!(
                "its floor ({}) is higher than this sector's ({})",
                there.floor.value, here.floor.value
            ))
        } else if there_floor.1 > here.floor.value {
            Some(format!(
                "it is a {} whose floor rises to {}, higher than this sector's ({})",
                kind_of(there),
                there_floor.1,
                here.floor.value
            ))
        } else if there.floor.value > here_floor.0 {
            Some(format!(
                "this sector is a {} whose floor goes down to {}, lower than the neighbour's ({})",
                kind_of(here),
                here_floor.0,
                there.floor.value
            ))
        } else if there_floor.1 > here_floor.0 {
            Some(format!(
                "it is a {} whose floor rises to {} and this sector a {} whose floor goes down to {}",
                kind_of(there),
                there_floor.1,
                kind_of(here),
                here_floor.0
            ))
        } else {
            None
        };
        if let Some(why) = message {
            errors.push((
                at,
                format!(
                    "portal to {} needs lower=TEXTURE: {why}, so a step shows below the opening",
                    there.label
                ),
            ));
        }
    }
}

/// Whether sectors `a` and `b` name each other in a floor or ceiling portal.
fn linked(source: &SourceMap, a: usize, b: usize) -> bool {
    let names = |from: usize, to: usize| {
        let sector = &source.sectors[from];
        [&sector.above, &sector.below]
            .into_iter()
            .any(|link| link.as_ref().is_some_and(|link| link.value == to))
    };
    names(a, b) || names(b, a)
}

/// Refuses two sectors whose insides overlap (issue 16): sectors may touch along walls and at
/// corners, but one piece of ground in two sectors would be drawn by both and the player could
/// stand in either. Exact: two convex outlines have disjoint insides if and only if the line
/// through some wall of one has the whole other outline on its outer side or on it (the
/// separating axis theorem; every outline is convex by now). A box test skips most pairs.
/// Sectors on different layers (`layer=`) may overlap: room over room.
fn check_overlaps(source: &SourceMap, outlines: &[Outline<'_>], errors: &mut Vec<Located>) {
    let corners: Vec<Vec<Point>> = outlines
        .iter()
        .map(|outline| {
            outline
                .walls
                .iter()
                .map(|wall| point(source, wall.start))
                .collect()
        })
        .collect();
    let boxes: Vec<(Point, Point)> = corners
        .iter()
        .map(|points| {
            let (mut low, mut high) = (points[0], points[0]);
            for &(x, y) in points {
                low = (low.0.min(x), low.1.min(y));
                high = (high.0.max(x), high.1.max(y));
            }
            (low, high)
        })
        .collect();
    // Every wall of `a` has the inside on its right (cross > 0): `b` lies wholly outside the
    // line through one of them, or on it.
    let separated_by_a_wall_of = |a: &[Point], b: &[Point]| {
        (0..a.len()).any(|index| {
            let (start, end) = (a[index], a[(index + 1) % a.len()]);
            b.iter().all(|&p| cross(start, end, p) <= 0)
        })
    };
    for later in 0..outlines.len() {
        for earlier in 0..later {
            let ((low_a, high_a), (low_b, high_b)) = (boxes[earlier], boxes[later]);
            let boxes_overlap = low_a.0 < high_b.0
                && low_b.0 < high_a.0
                && low_a.1 < high_b.1
                && low_b.1 < high_a.1;
            if !boxes_overlap
                || source.sectors[earlier].layer.value != source.sectors[later].layer.value
                || separated_by_a_wall_of(&corners[earlier], &corners[later])
                || separated_by_a_wall_of(&corners[later], &corners[earlier])
            {
                continue;
            }
            let (here, there) = (&source.sectors[later], &source.sectors[earlier]);
            errors.push((
                here.loc,
                format!(
                    "{} overlaps {} (line {}): some ground lies inside both; sectors may only meet along walls and at corners, so move or split their outlines (or put them on different layers with layer=, for room over room)",
                    here.label, there.label, there.loc.line
                ),
            ));
        }
    }
}

/// Formats a 24.8 value for messages.
fn fx8(value: i64) -> String {
    let text = format!("{:.4}", value as f64 / 256.0);
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// How far the player's start must be from every solid wall, in world units: the player's
/// radius. The game's collision keeps the eye this far from solid walls once it moves, but the
/// first frame is drawn from the start itself, and nearer a wall the renderer has known faults
/// (an eye within a 256th of a unit of a corner is drawn up to 29 % wrong: docs/RELIABILITY.md,
/// "Known faults"). docs/MAP_FORMAT.md states the same 16.
pub(crate) const START_CLEARANCE: i64 = 16;

/// Refuses a player start closer than [`START_CLEARANCE`] to a solid wall of any sector (a
/// wall of a neighbour that near would push the player's disc too). Portal lines are not
/// walls: the player crosses them. Exact integer arithmetic on the start's 24.8 position.
fn check_start_clearance(
    source: &SourceMap,
    outlines: &[Outline<'_>],
    place: &SourcePlace,
    errors: &mut Vec<Located>,
) {
    let p = (i128::from(place.x_fx8.value), i128::from(place.y_fx8.value));
    let clearance = i128::from(START_CLEARANCE) * 256;
    let mut nearest: Option<(f64, &OrientedWall<'_>)> = None;
    for wall in outlines.iter().flat_map(|o| &o.walls) {
        if wall.source.portal.is_some() {
            continue;
        }
        let scaled = |vertex: usize| {
            let (x, y) = point(source, vertex);
            (i128::from(x) * 256, i128::from(y) * 256)
        };
        let (a, b) = (scaled(wall.start), scaled(wall.end));
        let (ab, ap, bp) = (
            (b.0 - a.0, b.1 - a.1),
            (p.0 - a.0, p.1 - a.1),
            (p.0 - b.0, p.1 - b.1),
        );
        let along = ab.0 * ap.0 + ab.1 * ap.1;
        let length_squared = ab.0 * ab.0 + ab.1 * ab.1;
        // Squared distance to the segment as a fraction `numerator / denominator`.
        let (numerator, denominator) = if along <= 0 {
            (ap.0 * ap.0 + ap.1 * ap.1, 1)
        } else if along >= length_squared {
            (bp.0 * bp.0 + bp.1 * bp.1, 1)
        } else {
            let cross = ab.0 * ap.1 - ab.1 * ap.0;
            (cross * cross, length_squared)
        };
        if numerator < clearance * clearance * denominator {
            let distance = (numerator as f64 / denominator as f64).sqrt() / 256.0;
            if nearest.is_none_or(|(d, _)| distance < d) {
                nearest = Some((distance, wall));
            }
        }
    }
    if let Some((distance, wall)) = nearest {
        let label = |vertex: usize| source.vertices[vertex].label.as_str();
        // Rounded up to a 256th, the positions' resolution, so moving that far is enough.
        let short = (START_CLEARANCE as f64 - distance) * 256.0;
        errors.push((
            place.loc,
            format!(
                "player start at ({}, {}) is {} from the solid wall from {} to {} (line {}); move it at least {} further from that wall: the start must be {START_CLEARANCE} or more from every solid wall (the player's radius)",
                fx8(place.x_fx8.value),
                fx8(place.y_fx8.value),
                fx8((distance * 256.0).floor() as i64),
                label(wall.start),
                label(wall.end),
                wall.source.loc.line,
                fx8(short.ceil() as i64),
            ),
        ));
    }
}

/// Refuses the player's start or a thing (`what`, at `place`) in sector `sector` if it is a door
/// or a crusher: their ceilings come down to (or toward) the floor, on the start or through the
/// sprite. Lifts and platforms carry what stands on them.
fn check_not_in_closing_sector(
    source: &SourceMap,
    sector: usize,
    place: &SourcePlace,
    what: &str,
    errors: &mut Vec<Located>,
) {
    let sector = &source.sectors[sector];
    let Some(mover) = &sector.mover else {
        return;
    };
    let why = match mover.kind {
        MoverKind::Door => {
            "a door: it is closed when the map starts, its ceiling down on its floor"
        }
        MoverKind::Crusher => "a crusher: its ceiling keeps coming down toward its floor",
        MoverKind::Lift | MoverKind::Platform => return,
    };
    let fix = if what == "player start" {
        "start the player outside it"
    } else {
        "place the thing outside it (things may stand in lifts and platforms)"
    };
    errors.push((
        place.loc,
        format!(
            "{what} at ({}, {}) is in {}, {why}; {fix}",
            fx8(place.x_fx8.value),
            fx8(place.y_fx8.value),
            sector.label
        ),
    ));
}

/// A direction in the plane, as an integer vector (y down).
type Direction = (i64, i64);

fn perp_dot(a: Direction, b: Direction) -> i128 {
    i128::from(a.0) * i128::from(b.1) - i128::from(a.1) * i128::from(b.0)
}

/// Sorts directions by angle (atan2 order), exactly.
fn angle_order(a: &Direction, b: &Direction) -> std::cmp::Ordering {
    let half = |v: &Direction| u8::from(!(v.1 > 0 || (v.1 == 0 && v.0 > 0)));
    half(a).cmp(&half(b)).then_with(|| 0.cmp(&perp_dot(*a, *b)))
}

/// Refuses a map where a view could pass more than [`PORTAL_DEPTH_MAX`] portals in a row: the
/// renderer's walk stops there and leaves what lies beyond undrawn.
///
/// The rule, sound and checkable: a column's ray leaves each sector of its walk through the one
/// wall that owns the column, so every portal of a walk path is crossed by that ray outwards,
/// `cross(wall, d) < 0` for the ray's direction `d`. For one direction those crossings form an
/// acyclic graph of sectors (convex sectors that do not overlap are ordered along any
/// direction), and the longest path in it bounds every walk whose rays point that way. The
/// graph only changes where `d` is parallel to a portal, so one direction strictly between each
/// two consecutive portal directions covers all. The bound counts portals crossed in one general
/// direction, not only along one straight line, so it can refuse a winding run that no single
/// ray follows; it never accepts a map whose walk is cut. Only the sectors the player can reach
/// (through portals from the start's) count; a map of at most `PORTAL_DEPTH_MAX + 1` of them
/// passes at once.
fn check_portal_depth(
    source: &SourceMap,
    outlines: &[Outline<'_>],
    layer_links: &[LayerLink],
    start: usize,
    errors: &mut Vec<Located>,
) {
    // The walk also goes a level deeper through each floor or ceiling portal it passes, which
    // the runs below do not count: each link may take two levels (up and back down) off them.
    let crossings = layer_links
        .iter()
        .filter(|link| link.above != NO_LINK)
        .count();
    let limit = (PORTAL_DEPTH_MAX as usize).saturating_sub(2 * crossings);
    // Each portal as seen from its sector: (from, to, wall vector, the wall).
    let mut portals: Vec<Vec<(usize, Direction, &OrientedWall<'_>)>> =
        vec![Vec::new(); outlines.len()];
    for (from, outline) in outlines.iter().enumerate() {
        for wall in &outline.walls {
            if let Some(to) = &wall.source.portal {
                let (a, b) = (point(source, wall.start), point(source, wall.end));
                portals[from].push((to.value, (b.0 - a.0, b.1 - a.1), wall));
            }
        }
    }
    let mut reachable = vec![false; outlines.len()];
    let mut stack = vec![start];
    reachable[start] = true;
    while let Some(sector) = stack.pop() {
        let linked = layer_links.get(sector).into_iter().flat_map(|link| {
            [link.above, link.below]
                .into_iter()
                .filter(|&to| to != NO_LINK)
                .map(usize::from)
        });
        for to in portals[sector].iter().map(|&(to, _, _)| to).chain(linked) {
            if !reachable[to] {
                reachable[to] = true;
                stack.push(to);
            }
        }
    }
    if reachable.iter().filter(|&&r| r).count() <= limit + 1 {
        return;
    }
    let mut directions: Vec<Direction> = portals
        .iter()
        .enumerate()
        .filter(|(sector, _)| reachable[*sector])
        .flat_map(|(_, list)| list.iter().map(|&(_, v, _)| v))
        .flat_map(|v| [v, (-v.0, -v.1)])
        .collect();
    directions.sort_by(angle_order);
    directions.dedup_by(|a, b| angle_order(a, b).is_eq());
    // The longest run found: its length in portals and its first sector.
    let mut worst: Option<(usize, usize, Vec<usize>)> = None;
    for (i, &a) in directions.iter().enumerate() {
        let b = directions[(i + 1) % directions.len()];
        // Strictly between a and b (going round in angle order): their sum when the arc is
        // under a half turn, else a turned a quarter turn onwards.
        let d = if perp_dot(a, b) > 0 {
            (a.0 + b.0, a.1 + b.1)
        } else {
            (-a.1, a.0)
        };
        match longest_run(&portals, &reachable, d) {
            Some((length, path)) => {
                if length > limit && worst.as_ref().is_none_or(|w| length > w.0) {
                    worst = Some((length, path[0], path));
                }
            }
            None => {
                // A loop of portals all crossed one way: only overlapping sectors make one. The
                // plain bound, the number of sectors reachable, is over the limit (else this
                // check returned above), so the map is refused.
                worst = Some((usize::MAX, start, Vec::new()));
                break;
            }
        }
    }
    let Some((length, first, path)) = worst else {
        return;
    };
    let label = |sector: usize| source.sectors[sector].label.as_str();
    let (loc, message) = if path.len() >= 2 {
        let first_portal = portals[first]
            .iter()
            .find(|&&(to, _, _)| to == path[1])
            .and_then(|&(_, _, wall)| wall.source.portal.as_ref())
            .map_or(source.sectors[first].loc, |p| p.loc);
        (
            first_portal,
            format!(
                "a view from {} can pass {length} portals in a row (through {} to {}), more than the {limit} the renderer follows: what lies beyond would be left undrawn; close the run with a solid wall or shorten it (a run counts portals all crossed in one general direction)",
                label(first),
                label(path[1]),
                label(path[path.len() - 1])
            ),
        )
    } else {
        (
            source.sectors[first].loc,
            format!(
                "portals from {} lead round in a loop, all crossed the same way, which only overlapping sectors allow; fix the outlines",
                label(first)
            ),
        )
    };
    errors.push((loc, message));
}

/// The longest chain of portals crossed outwards by direction `d` (`cross(wall, d) < 0`),
/// starting in a reachable sector: its length in portals and its sectors. `None` if those
/// crossings form a loop.
fn longest_run(
    portals: &[Vec<(usize, Direction, &OrientedWall<'_>)>],
    reachable: &[bool],
    d: Direction,
) -> Option<(usize, Vec<usize>)> {
    const UNSEEN: u8 = 0;
    const OPEN: u8 = 1;
    const DONE: u8 = 2;
    let n = portals.len();
    let mut state = vec![UNSEEN; n];
    // Longest run from each sector, and the next sector on it.
    let mut length = vec![0usize; n];
    let mut next = vec![usize::MAX; n];
    for root in (0..n).filter(|&s| reachable[s]) {
        if state[root] != UNSEEN {
            continue;
        }
        // Depth-first, iterative: (sector, index of the next portal to try).
        let mut stack = vec![(root, 0usize)];
        state[root] = OPEN;
        while let Some(&(sector, index)) = stack.last() {
            let top = stack.len() - 1;
            let Some(&(to, wall, _)) = portals[sector].get(index) else {
                state[sector] = DONE;
                stack.pop();
                continue;
            };
            if perp_dot(wall, d) >= 0 {
                stack[top].1 += 1;
                continue;
            }
            match state[to] {
                UNSEEN => {
                    // Visit `to` first; this portal is looked at again once it is done.
                    state[to] = OPEN;
                    stack.push((to, 0));
                }
                OPEN => return None,
                _ => {
                    if length[to] + 1 > length[sector] {
                        length[sector] = length[to] + 1;
                        next[sector] = to;
                    }
                    stack[top].1 += 1;
                }
            }
        }
    }
    let first = (0..n)
        .filter(|&s| reachable[s])
        .max_by_key(|&s| length[s])?;
    let mut path = vec![first];
    while next[*path.last()?] != usize::MAX {
        path.push(next[*path.last()?]);
    }
    Some((length[first], path))
}

/// Finds the one sector strictly containing `place`.
fn locate(
    source: &SourceMap,
    outlines: &[Outline<'_>],
    place: &SourcePlace,
    what: &str,
    errors: &mut Vec<Located>,
) -> u16 {
    let p = (place.x_fx8.value, place.y_fx8.value);
    let scaled = |vertex: usize| {
        let (x, y) = point(source, vertex);
        (x * 256, y * 256)
    };
    let mut inside = Vec::new();
    let mut on_line = Vec::new();
    for (index, outline) in outlines.iter().enumerate() {
        let sides: Vec<i128> = outline
            .walls
            .iter()
            .map(|w| cross(scaled(w.start), scaled(w.end), p))
            .collect();
        if sides.iter().all(|&s| s > 0) {
            inside.push(index);
        } else if sides.iter().all(|&s| s >= 0) {
            on_line.push(index);
        }
    }
    // Where sectors of several layers hold the place, the line's `layer=` (0 unless given)
    // picks among them.
    let layer_of = |index: &usize| source.sectors[*index].layer.value;
    let layers: Vec<i64> = inside.iter().chain(&on_line).map(layer_of).collect();
    if let Some(wanted) = place
        .layer
        .as_ref()
        .map(|layer| layer.value)
        .or_else(|| layers.iter().any(|&l| l != layers[0]).then_some(0))
    {
        inside.retain(|index| layer_of(index) == wanted);
        on_line.retain(|index| layer_of(index) == wanted);
        if inside.is_empty() && on_line.is_empty() && !layers.is_empty() {
            errors.push((
                place.layer.as_ref().map_or(place.loc, |layer| layer.loc),
                format!(
                    "{what} is in no sector of layer {wanted} here; give layer= one of the layers of the sectors that hold it ({})",
                    layers.iter().map(i64::to_string).collect::<Vec<_>>().join(", ")
                ),
            ));
            return NO_PORTAL;
        }
    }
    let at = format!("({}, {})", fx8(p.0), fx8(p.1));
    let off_the_line = if what == "player start" {
        format!("move it at least {START_CLEARANCE} from every solid wall")
    } else {
        "move it off the line".to_string()
    };
    match (inside.as_slice(), on_line.as_slice()) {
        ([index], []) => return u16::try_from(*index).unwrap_or(NO_PORTAL),
        (_, [index, ..]) => errors.push((
            place.loc,
            format!(
                "{what} at {at} lies on a wall line of {}; {off_the_line}",
                source.sectors[*index].label
            ),
        )),
        ([], []) => errors.push((
            place.loc,
            format!("{what} at {at} is in no sector; move it inside one"),
        )),
        // Overlapping sectors are refused before a place is located (`check_overlaps`); kept
        // so that a place is never silently given to one of two.
        ([a, b, ..], []) => errors.push((
            place.loc,
            format!(
                "{what} at {at} is inside both {} and {}; those sectors overlap, fix their outlines",
                source.sectors[*a].label, source.sectors[*b].label
            ),
        )),
    }
    NO_PORTAL
}

#[allow(clippy::too_many_arguments)]
fn tables(
    name: &str,
    source: &SourceMap,
    catalog: &Catalog,
    outlines: &[Outline<'_>],
    middles: &[Vec<Option<&SourceWall>>],
    player_sector: u16,
    thing_sectors: &[u16],
    fits: Vec<ThingFit>,
    sector_slopes: &[Option<SectorSlope>],
    layer_links: Vec<LayerLink>,
) -> (CompiledMap, Vec<ThingFit>) {
    // Each distinct pair of planes once, so equal indices mean equal planes.
    let mut slopes: Vec<SectorSlope> = Vec::new();
    let slope_index: Vec<u16> = sector_slopes
        .iter()
        .map(|slope| match slope {
            None => NO_SLOPE,
            Some(slope) => match slopes.iter().position(|known| known == slope) {
                Some(at) => at as u16,
                None => {
                    slopes.push(*slope);
                    (slopes.len() - 1) as u16
                }
            },
        })
        .collect();
    // Every reference was checked above, so these lookups cannot fail.
    let mut ignore = Vec::new();
    let mut texture = |name: &Option<Spanned<String>>| {
        name.as_ref()
            .map_or(NO_TEXTURE, |n| catalog.texture(n, &mut ignore))
    };
    // Keep only the vertices some wall uses, in declaration order.
    let mut used = vec![false; source.vertices.len()];
    for wall in outlines.iter().flat_map(|o| &o.walls) {
        used[wall.start] = true;
    }
    let mut new_index = vec![0u16; source.vertices.len()];
    let mut vertices = Vec::new();
    for (index, vertex) in source.vertices.iter().enumerate() {
        if used[index] {
            new_index[index] = vertices.len() as u16;
            vertices.push(Vertex {
                x: vertex.x.value as i32,
                y: vertex.y.value as i32,
            });
        }
    }
    let mut walls = Vec::new();
    let mut sectors = Vec::new();
    let mut triggers = Vec::new();
    let mut movers = Vec::new();
    let mut lights = Vec::new();
    for ((sector, outline), middles) in source.sectors.iter().zip(outlines).zip(middles) {
        let first_wall = walls.len() as u16;
        for (wall, middle) in outline.walls.iter().zip(middles) {
            let trigger = trigger(wall.source, walls.len() as u16, catalog);
            let switch = match trigger {
                Some(Trigger {
                    kind: TRIGGER_SWITCH,
                    ..
                }) => WALL_SWITCH,
                _ => 0,
            };
            triggers.extend(trigger);
            let (middle, flags) = match middle.and_then(|m| Some((m, m.middle.as_ref()?))) {
                Some((words, name)) => (
                    catalog.sprite(name, &mut Vec::new()),
                    if words.blocks.is_some() {
                        WALL_MIDDLE_BLOCKS
                    } else {
                        0
                    } | if words.translucent.is_some() {
                        WALL_MIDDLE_TRANSLUCENT
                    } else {
                        0
                    },
                ),
                None => (NO_TEXTURE, 0),
            };
            walls.push(Wall {
                start: new_index[wall.start],
                end: new_index[wall.end],
                portal: wall
                    .source
                    .portal
                    .as_ref()
                    .map_or(NO_PORTAL, |p| p.value as u16),
                texture: texture(&wall.source.texture),
                upper_texture: texture(&wall.source.upper),
                lower_texture: texture(&wall.source.lower),
                x_offset: wall.source.x_offset.value as i16,
                y_offset: wall.source.y_offset.value as i16,
                length_fx8: wall_length_fx8(
                    vertices[usize::from(new_index[wall.start])],
                    vertices[usize::from(new_index[wall.end])],
                ),
                middle,
                flags: flags | switch,
            });
        }
        sectors.push(Sector {
            first_wall,
            wall_count: outline.walls.len() as u16,
            floor_z: sector.floor.value as i32,
            ceil_z: sector.ceil.value as i32,
            floor_texture: texture(&Some(sector.floor_texture.clone())),
            ceil_texture: match &sector.ceiling {
                CeilingSource::Sky => SKY,
                CeilingSource::Texture(name) => texture(&Some(name.clone())),
            },
            light: sector.light,
            links: layer_links.get(sectors.len()).map_or(0, |link| {
                (u8::from(link.above != NO_LINK) * LINK_CEILING)
                    | (u8::from(link.below != NO_LINK) * LINK_FLOOR)
            }),
            slope: slope_index[sectors.len()],
        });
        if let Some(mover) = mover(sector, (sectors.len() - 1) as u16) {
            movers.push(mover);
        }
        if let Some(light) = &sector.light_effect {
            lights.push(Light {
                sector: (sectors.len() - 1) as u16,
                kind: light.kind,
                low: light.low.value,
                period: light.period,
                tag: light.tag.as_ref().map_or(0, |tag| tag.value),
            });
        }
    }
    let place = |p: &SourcePlace| (p.x_fx8.value as i32, p.y_fx8.value as i32, p.angle);
    let (x_fx8, y_fx8, angle) = place(&source.player);
    let things = source
        .things
        .iter()
        .zip(thing_sectors)
        .map(|(thing, &sector)| {
            let (x_fx8, y_fx8, angle) = place(&thing.place);
            Thing {
                x_fx8,
                y_fx8,
                angle,
                sprite: catalog.sprite(&thing.sprite, &mut ignore),
                sector,
                z: thing.options.z as i16,
                radius: thing.options.radius.as_ref().map_or(0, |r| r.value as u16),
                flags: if thing.options.hanging {
                    THING_HANGING
                } else {
                    0
                } | if thing.options.solid { THING_SOLID } else { 0 }
                    | if thing.options.translucent {
                        THING_TRANSLUCENT
                    } else {
                        0
                    },
                frame_ticks: thing.options.frame_ticks,
            }
        })
        .zip(fits)
        .collect();
    let (things, fits, sector_things) = group_things_by_sector(things, sectors.len());
    let wall_twins = wall_twins(&walls, &sectors);
    let map = CompiledMap {
        name: name.to_string(),
        vertices,
        walls,
        sectors,
        things,
        sector_things,
        movers,
        triggers,
        lights,
        wall_twins,
        slopes,
        layer_links,
        player_start: PlayerStart {
            x_fx8,
            y_fx8,
            angle,
            sector: player_sector,
            size: source.player_size,
        },
    };
    (map, fits)
}

/// [`MapTables::wall_twins`]: every wall's [`find_twin`], or [`NO_TWIN`].
fn wall_twins(walls: &[Wall], sectors: &[Sector]) -> Vec<u16> {
    let mut twins = vec![NO_TWIN; walls.len()];
    for (sector_index, sector) in sectors.iter().enumerate() {
        let first = usize::from(sector.first_wall);
        let count = usize::from(sector.wall_count);
        for (index, twin) in twins.iter_mut().enumerate().skip(first).take(count) {
            if let Some(found) = find_twin(walls, sectors, sector_index as u16, index) {
                *twin = found as u16;
            }
        }
    }
    twins
}

/// The [`Trigger`] of a wall (index `wall_index` in the walls table) whose line gives
/// `switch=TEX tag=N` or `trigger=N`, if it does; its words are checked by now.
fn trigger(wall: &SourceWall, wall_index: u16, catalog: &Catalog) -> Option<Trigger> {
    let (tag, kind, used_texture) = match (&wall.switch, &wall.tag, &wall.trigger) {
        (Some(texture), Some(tag), _) => (
            tag.value,
            TRIGGER_SWITCH,
            catalog.texture(texture, &mut Vec::new()),
        ),
        (_, _, Some(tag)) => (tag.value, TRIGGER_LINE, NO_TEXTURE),
        _ => return None,
    };
    Some(Trigger {
        wall: wall_index,
        tag,
        kind,
        thrown: 0,
        used_texture,
    })
}

/// The [`Mover`] of `sector` (index `sector_index`), if it moves; its heights are checked by
/// now. A door is drawn open and starts closed; a lift is drawn raised and starts there; a
/// platform starts at the floor drawn; a crusher starts open.
fn mover(sector: &SourceSector, sector_index: u16) -> Option<Mover> {
    let written = sector.mover.as_ref()?;
    let (kind, low, high) = mover_range(sector)?;
    let (kind, start) = match kind {
        MoverKind::Door => (MOVER_DOOR, low),
        MoverKind::Lift => (MOVER_LIFT, high),
        MoverKind::Platform => (MOVER_PLATFORM, sector.floor.value),
        MoverKind::Crusher => (MOVER_CRUSHER, high),
    };
    let started_by_use =
        matches!(written.kind, MoverKind::Door | MoverKind::Lift) && written.locked.is_none();
    let flags = if started_by_use { MOVER_ON_USE } else { 0 }
        | if written.touch { MOVER_ON_TOUCH } else { 0 };
    Some(Mover {
        sector: sector_index,
        kind,
        flags,
        low: low as i32,
        high: high as i32,
        speed: written.speed,
        wait: written.wait,
        tag: written.tag.as_ref().map_or(0, |tag| tag.value),
        start: start as i32,
    })
}

/// `floor(256·√(Δx² + Δy²))`: a wall's length in 24.8, as [`Wall::length_fx8`] stores it. Within
/// the declared limits (`WALL_LENGTH_MAX`) it fits i32.
pub fn wall_length_fx8(a: Vertex, b: Vertex) -> i32 {
    let (dx, dy) = (i64::from(b.x - a.x), i64::from(b.y - a.y));
    // (length · 256)² = (dx² + dy²) · 65536.
    (((dx * dx + dy * dy) as u64) << 16).isqrt() as i32
}

/// `things` (each with what goes along with it) in sector order (stable: a sector's things keep
/// their order in the source), and where each sector's start, with one entry past the last
/// ([`MapTables::sector_things`]); no entries when there are no things.
fn group_things_by_sector<T>(
    mut things: Vec<(Thing, T)>,
    sector_count: usize,
) -> (Vec<Thing>, Vec<T>, Vec<u16>) {
    if things.is_empty() {
        return (Vec::new(), Vec::new(), Vec::new());
    }
    // Each sector's solid things first: the collision reads a sector's things only while they
    // are solid.
    things.sort_by_key(|(thing, _)| (thing.sector, thing.flags & THING_SOLID == 0));
    let starts = (0..=sector_count)
        .map(|sector| {
            things.partition_point(|(thing, _)| usize::from(thing.sector) < sector) as u16
        })
        .collect();
    let (things, along) = things.into_iter().unzip();
    (things, along, starts)
}
