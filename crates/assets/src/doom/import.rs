//! A WAD's maps compiled for the ROM, as an asset directory's are ([`crate::compile_dir`]):
//! each map cut into convex pieces ([`super::partition()`]), mapped onto a map source
//! (`super::convert`) and checked by the map compiler itself, then the textures, flats and sky
//! the maps use drawn from the WAD in Doom's palette, and Doom's light tables as portalcast's
//! colormap.
//!
//! What portalcast's formats cannot hold as Doom has it is fitted, and said in the import
//! report ([`Compiled::import_report`]):
//! - a texture side that is not a power of two (Doom's DOOR1 is 64×72) is widened to the next
//!   one by repeating the texture (rows 72 to 127 repeat rows 0 to 55), as Doom's later ports
//!   wrap it; a side over 256 is cut to 256;
//! - the sky is the first map's (Doom's `SKY1` to `SKY4` by episode or map number), 256 columns
//!   a quarter turn as in Doom, so repeated four times round;
//! - what `super::convert` leaves out (closed sectors other than manual doors, specials, things)
//!   and the walls Doom leaves without a texture, which take a black stand-in.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use image::{Rgba, RgbaImage};
use portalcast_format::{Colormap, LIGHT_NEUTRAL, NO_TEXTURE};

use super::colours::DoomPalette;
use super::convert::{self, StandIns, FLAT_PREFIX, STAND_IN_TEXTURE};
use super::graphics::{self, IndexedImage, Textures};
use super::level::{is_map_name, DoomLevel};
use super::partition::partition;
use super::things::{self, ComposedSet};
use super::wad::Wad;
use super::DoomError;
use crate::images::{
    SKY_HEIGHT_MAX, SKY_HEIGHT_MIN, SKY_WIDTH_MAX, TEXTURE_SIDE_MAX, TEXTURE_SIDE_MIN,
};
use crate::map_build::{self, Catalog, CompiledMap};
use crate::palette::{colormap_of, Quantiser};
use crate::source::SourceMap;
use crate::sprite_sets::SetSource;
use crate::{
    texels, Compiled, CompiledSky, CompiledSprite, CompiledSpriteSet, CompiledTexture, Usage,
};

/// Where Debian's `freedoom` package puts its WADs.
pub const FREEDOOM_DIR: &str = "/usr/share/games/doom";

/// Sky columns a full turn in Doom (`ANGLETOSKYSHIFT`: 1024 columns of a 256-wide sky texture).
const DOOM_SKY_COLUMNS_PER_TURN: u32 = 1024;

/// What to build from a WAD.
#[derive(Clone, Debug, Default)]
pub struct WadRequest {
    /// The WAD with the maps (an IWAD, or a PWAD made in an editor).
    pub wad: PathBuf,
    /// The IWAD whose graphics a PWAD's maps use; `None`: Freedoom's (`freedoom2.wad` for
    /// `MAPxx` maps, `freedoom1.wad` for `ExMy`), from [`FREEDOOM_DIR`]. Unused for an IWAD.
    pub iwad: Option<PathBuf>,
    /// The maps to build, by name (`E1M1`); `None`: all the WAD has.
    pub maps: Option<Vec<String>>,
}

/// The IWAD a PWAD with maps `maps` uses by default: Freedoom's, Phase 2 for `MAPxx` maps.
pub fn default_iwad(maps: &[String]) -> PathBuf {
    let doom2 = maps.iter().any(|name| name.starts_with("MAP"));
    Path::new(FREEDOOM_DIR).join(if doom2 {
        "freedoom2.wad"
    } else {
        "freedoom1.wad"
    })
}

/// The sky texture Doom shows over map `map` (`R_InitSkyMap` and `G_InitNew`): by episode for
/// `ExMy`, by map number for `MAPxx` (`SKY1` up to MAP11, `SKY2` up to MAP20, `SKY3` after).
fn sky_texture(map: &str) -> String {
    let number = |text: &str| text.parse::<u32>().unwrap_or(1);
    let sky = if let Some(rest) = map.strip_prefix("MAP") {
        match number(rest) {
            0..=11 => 1,
            12..=20 => 2,
            _ => 3,
        }
    } else {
        number(&map[1..2]).clamp(1, 4)
    };
    format!("SKY{sky}")
}

/// The maps of `wad` named by the request (all of them if it names none), in order.
fn map_names(wad: &Wad, wanted: Option<&[String]>) -> Result<Vec<String>, DoomError> {
    let mut present: Vec<String> = wad
        .names()
        .filter(|name| is_map_name(name))
        .map(str::to_string)
        .collect();
    present.dedup();
    let Some(wanted) = wanted else {
        if present.is_empty() {
            return Err(DoomError::new(
                wad.path(),
                None,
                "holds no map (no ExMy or MAPxx lump): name a WAD with maps".to_string(),
            ));
        }
        return Ok(present);
    };
    let mut names = Vec::new();
    for name in wanted {
        let name = name.trim().to_ascii_uppercase();
        if !present.contains(&name) {
            return Err(DoomError::new(
                wad.path(),
                Some(&name),
                format!(
                    "no such map in this WAD; it has {}: fix PORTALCAST_MAPS",
                    present.join(", ")
                ),
            ));
        }
        if !names.contains(&name) {
            names.push(name);
        }
    }
    Ok(names)
}

/// Portalcast's colormap from Doom's `COLORMAP`: row `r` below the neutral row (16) is Doom's
/// row `2·(16 − r)` (the last, 31, for row 0), so that a sector's light level, half Doom's
/// ([`convert::light_level`]), darkens as Doom's does; the neutral row and those above it are
/// the identity (Doom never brightens). Indices go through `palette` (Doom's black is not
/// index 0 here).
fn colormap(doom_rows: &[[u8; 256]], palette: &DoomPalette) -> Box<Colormap> {
    let neutral = usize::from(LIGHT_NEUTRAL >> 3);
    colormap_of(|row, index| {
        if row >= neutral {
            index as u8
        } else {
            let doom_row = (2 * (neutral - row)).min(31);
            palette.index(doom_rows[doom_row][index])
        }
    })
}

/// `image` as an opaque RGBA picture `width × height`, repeated to fill it (or cut), each texel
/// the colour the GBA shows for it; Doom's gaps (nothing drawn) black, as Doom's index 0.
fn picture(
    image: &IndexedImage,
    width: u32,
    height: u32,
    palette: &DoomPalette,
    quantiser: &Quantiser,
) -> RgbaImage {
    let (source_width, source_height) = (u32::from(image.width), u32::from(image.height));
    RgbaImage::from_fn(width, height, |x, y| {
        let texel = image
            .at((x % source_width) as u16, (y % source_height) as u16)
            .unwrap_or(0);
        let [r, g, b] = quantiser.shown(palette.index(texel));
        Rgba([r, g, b, 255])
    })
}

/// How many stand-in textures of `source` can show: on solid walls, and on step strips whose
/// step exists or may come as the movers move (the neighbour's ceiling at its lowest below this
/// sector's at its highest, its floor at its highest above this one's at its lowest; not
/// between two pieces of one mover, which move together). A portal with equal heights on
/// both sides shows no strip, so Doom leaves those textures out, and their stand-ins are never
/// drawn.
fn shown_stand_ins(source: &SourceMap) -> usize {
    let heights = map_build::plane_spans;
    let is_stand_in = |texture: &Option<crate::source::Spanned<String>>| {
        texture
            .as_ref()
            .is_some_and(|t| t.value == STAND_IN_TEXTURE)
    };
    let mut shown = 0;
    for sector in &source.sectors {
        for wall in &sector.walls {
            let Some(behind) = wall
                .portal
                .as_ref()
                .and_then(|p| source.sectors.get(p.value))
            else {
                shown += usize::from(is_stand_in(&wall.texture));
                continue;
            };
            // Two pieces of one mover move together: the cut between them shows nothing.
            let one_mover = match (&sector.mover, &behind.mover) {
                (Some(a), Some(b)) => {
                    a.kind == b.kind
                        && a.tag.as_ref().map(|t| t.value) == b.tag.as_ref().map(|t| t.value)
                        && (sector.floor.value, sector.ceil.value)
                            == (behind.floor.value, behind.ceil.value)
                }
                _ => false,
            };
            if one_mover {
                continue;
            }
            let ((_, behind_floor_highest), (behind_ceil_lowest, _)) = heights(behind);
            let ((own_floor_lowest, _), (_, own_ceil_highest)) = heights(sector);
            let upper = behind_ceil_lowest < own_ceil_highest;
            let lower = behind_floor_highest > own_floor_lowest;
            shown += usize::from(upper && is_stand_in(&wall.upper));
            shown += usize::from(lower && is_stand_in(&wall.lower));
        }
    }
    shown
}

/// Most a thing is moved to fit its piece, in world units: less than a Doom monster's radius.
const NUDGE_MAX: i64 = 16;

/// `place` (24.8 units) moved by the fewest whole units, at most [`NUDGE_MAX`], that put a disc
/// of `radius` around it inside the sector of `sectors` it lies in, if that exists.
fn nudged(
    sectors: &[crate::source::SourceSector],
    vertices: &[crate::source::SourceVertex],
    place: (i64, i64),
    radius: i64,
) -> Option<(i64, i64)> {
    let corner = |index: usize| {
        let vertex = &vertices[index];
        (vertex.x.value as f64, vertex.y.value as f64)
    };
    // The least distance from `p` to the lines of `sector`'s walls, negative outside.
    let clearance = |sector: &crate::source::SourceSector, p: (f64, f64)| {
        let walls = || {
            sector
                .walls
                .iter()
                .map(|w| (corner(w.start), corner(w.end)))
        };
        let area: f64 = walls().map(|(a, b)| a.0 * b.1 - b.0 * a.1).sum();
        walls()
            .map(|(a, b)| {
                let cross = (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
                cross * area.signum() / (b.0 - a.0).hypot(b.1 - a.1)
            })
            .fold(f64::INFINITY, f64::min)
    };
    let at = |p: (i64, i64)| (p.0 as f64 / 256.0, p.1 as f64 / 256.0);
    let sector = sectors
        .iter()
        .find(|sector| clearance(sector, at(place)) > 0.0)?;
    let mut steps: Vec<(i64, i64)> = (-NUDGE_MAX..=NUDGE_MAX)
        .flat_map(|dx| (-NUDGE_MAX..=NUDGE_MAX).map(move |dy| (dx, dy)))
        .filter(|(dx, dy)| dx * dx + dy * dy <= NUDGE_MAX * NUDGE_MAX)
        .collect();
    steps.sort_by_key(|(dx, dy)| dx * dx + dy * dy);
    // A 256th over the radius: the compiler's test is exact, this one is in f64.
    let needed = radius as f64 + 1.0 / 256.0;
    steps
        .into_iter()
        .map(|(dx, dy)| (place.0 + dx * 256, place.1 + dy * 256))
        .find(|&p| clearance(sector, at(p)) >= needed)
}

/// A sprite's picture: Doom's palette colours, transparent where nothing is drawn.
fn sprite_picture(image: &IndexedImage, palette: &DoomPalette, quantiser: &Quantiser) -> RgbaImage {
    RgbaImage::from_fn(
        u32::from(image.width),
        u32::from(image.height),
        |x, y| match image.at(x as u16, y as u16) {
            Some(texel) => {
                let [r, g, b] = quantiser.shown(palette.index(texel));
                Rgba([r, g, b, 255])
            }
            None => Rgba([0, 0, 0, 0]),
        },
    )
}

/// The sprite sets the things of `sources` show, composed from `wad`'s sprite lumps, and the
/// portal middles its two-sided lines show, from its wall `textures`, by name. A set that
/// cannot be is reported, and its things (or its lines' middles) are left out.
fn sprite_sets(
    wad: &Wad,
    textures: &Textures,
    sources: &mut [(String, SourceMap)],
    report: &mut Vec<String>,
) -> BTreeMap<String, ComposedSet> {
    let mut sets = BTreeMap::new();
    let mut failed = BTreeMap::new();
    for (name, source) in sources.iter_mut() {
        let before = source.things.len();
        source.things.retain(|thing| {
            let set_name = &thing.sprite.value;
            if sets.contains_key(set_name) {
                return true;
            }
            if failed.contains_key(set_name) {
                return false;
            }
            let composed = things::kind_of_set(set_name)
                .ok_or_else(|| format!("no thing kind shows {set_name}"))
                .and_then(|kind| things::compose_set(wad, kind));
            match composed {
                Ok(set) => {
                    sets.insert(set_name.clone(), set);
                    true
                }
                Err(why) => {
                    failed.insert(set_name.clone(), why);
                    false
                }
            }
        });
        if source.things.len() < before {
            report.push(format!(
                "{name}: {} things whose sprites cannot be composed are left out",
                before - source.things.len()
            ));
        }
    }
    for (set_name, why) in failed {
        report.push(format!("sprite set {set_name}: {why}"));
    }
    // The two-sided lines' middle textures, each a sprite set of one still image.
    let mut failed_middles = BTreeMap::new();
    for (_, source) in sources.iter_mut() {
        let walls = source
            .sectors
            .iter_mut()
            .flat_map(|sector| &mut sector.walls);
        for wall in walls {
            let Some(set_name) = wall.middle.as_ref().map(|middle| middle.value.clone()) else {
                continue;
            };
            if !sets.contains_key(&set_name) && !failed_middles.contains_key(&set_name) {
                let texture = set_name
                    .trim_start_matches(convert::MIDDLE_PREFIX)
                    .to_ascii_uppercase();
                match middle_image(wad, textures, &texture) {
                    Ok(image) => {
                        sets.insert(
                            set_name.clone(),
                            ComposedSet {
                                frames: 1,
                                rotations: 1,
                                images: vec![image],
                            },
                        );
                    }
                    Err(why) => {
                        failed_middles.insert(set_name.clone(), why);
                    }
                }
            }
            if failed_middles.contains_key(&set_name) {
                wall.middle = None;
                wall.blocks = None;
            }
        }
    }
    for (set_name, why) in failed_middles {
        report.push(format!(
            "middle texture {set_name}: {why}: those lines show none"
        ));
    }
    sets
}

/// Wall texture `name` composed as a portal middle's image: transparent where no patch draws,
/// at most `SIDE_MAX` a side, with something drawn.
fn middle_image(wad: &Wad, textures: &Textures, name: &str) -> Result<IndexedImage, String> {
    let image = textures.compose(wad, name).map_err(|error| error.message)?;
    if image.width > 256 || image.height > 256 {
        return Err(format!(
            "{}x{} is more than 256 a side",
            image.width, image.height
        ));
    }
    if image.gaps() == image.texels.len() {
        return Err("nothing is drawn".to_string());
    }
    Ok(image)
}

/// The power-of-two side a texture side `side` becomes (`TEXTURE_SIDE_MIN..=TEXTURE_SIDE_MAX`).
fn texture_side(side: u16) -> u32 {
    u32::from(side)
        .next_power_of_two()
        .clamp(TEXTURE_SIDE_MIN, TEXTURE_SIDE_MAX)
}

/// The error `error` with the map that first uses the texture named in it.
fn used_by(mut error: DoomError, map: &str) -> DoomError {
    error.message = format!("{} (used by map {map})", error.message);
    error
}

/// Compiles the maps `request` names, with every texture, flat and sky they use, into an asset
/// set like [`crate::compile_dir`]'s. Errors name the WAD, the map and the lump (or the piece
/// and linedef, for the map compiler's findings); nothing is returned on any error.
pub fn compile_wad(request: &WadRequest) -> Result<Compiled, Vec<DoomError>> {
    let one = |error: DoomError| vec![error];
    let wad = Wad::open(&request.wad).map_err(one)?;
    let names = map_names(&wad, request.maps.as_deref()).map_err(one)?;
    let mut files_read = vec![request.wad.clone()];
    let graphics_wad = if wad.is_iwad() {
        wad.clone()
    } else {
        let iwad_path = request.iwad.clone().unwrap_or_else(|| default_iwad(&names));
        let iwad = Wad::open(&iwad_path).map_err(|mut error| {
            error.message = format!(
                "{}; a PWAD's textures come from an IWAD: set PORTALCAST_IWAD to one",
                error.message
            );
            vec![error]
        })?;
        files_read.push(iwad_path);
        Wad::over(&wad, &iwad)
    };

    let wall_textures = Textures::read(&graphics_wad).map_err(one)?;
    let mut errors = Vec::new();
    let mut report = Vec::new();
    let mut sources = Vec::new();
    let mut all_names = Vec::new();
    for name in &names {
        let level = match DoomLevel::read(&wad, name) {
            Ok(level) => level,
            Err(error) => {
                errors.push(error);
                continue;
            }
        };
        let pieces = match partition(&level) {
            Ok(pieces) => pieces,
            Err(error) => {
                errors.push(DoomError::new(
                    wad.path(),
                    Some(name),
                    format!("cannot cut it into convex pieces: {error}"),
                ));
                continue;
            }
        };
        report.extend(
            convert::import_report(&level, &pieces)
                .into_iter()
                .map(|line| format!("{name}: {line}")),
        );
        let (source, used) = convert::source(&level, &pieces, StandIns::On, &|name| {
            wall_textures.def(name).map(|def| (def.width, def.height))
        });
        let stand_ins = shown_stand_ins(&source);
        if stand_ins > 0 {
            report.push(format!(
                "{name}: {stand_ins} wall(s) or step strip(s) Doom leaves without a texture show black ({STAND_IN_TEXTURE})"
            ));
        }
        all_names.extend(used);
        sources.push((name.clone(), source));
    }
    let sets = sprite_sets(&graphics_wad, &wall_textures, &mut sources, &mut report);
    let mut catalog = Catalog::new(all_names, sets.keys().cloned(), true);
    for (set_name, set) in &sets {
        let first = &set.images[0];
        catalog = catalog
            .with_sprite_frames(set_name, set.frames, set.rotations)
            .with_sprite_size(set_name, first.width, first.height);
    }
    let size = |sprite: u16| {
        let set = sets.get(catalog.sprite_sets().get(usize::from(sprite))?)?;
        Some((set.images[0].width, set.images[0].height))
    };
    let mut maps: Vec<CompiledMap> = Vec::new();
    for (name, source) in &mut sources {
        let mut built = map_build::build(name, source, &catalog);
        // Things whose sprite does not fit their piece are moved a little to fit it, or else
        // left out, and the map built again.
        type Built = Result<
            (
                CompiledMap,
                Vec<map_build::FlatUse>,
                Vec<map_build::ThingFit>,
            ),
            Vec<crate::diag::Located>,
        >;
        let misfits = |built: &Built| -> std::collections::BTreeSet<usize> {
            match built {
                Ok((map, _, fits)) => map_build::misfits(map, fits, size)
                    .into_iter()
                    .map(convert::thing_of_loc)
                    .collect(),
                Err(_) => Default::default(),
            }
        };
        let out = misfits(&built);
        if !out.is_empty() {
            let SourceMap {
                sectors,
                vertices,
                things,
                ..
            } = &mut *source;
            let mut moved = 0;
            for thing in things.iter_mut() {
                let set = sets.get(&thing.sprite.value);
                if !out.contains(&convert::thing_of_loc(thing.place.loc)) || set.is_none() {
                    continue;
                }
                let radius = set.map_or(0, |set| i64::from(set.images[0].width.div_ceil(2)));
                let place = (thing.place.x_fx8.value, thing.place.y_fx8.value);
                if let Some((x, y)) = nudged(sectors, vertices, place, radius) {
                    thing.place.x_fx8.value = x;
                    thing.place.y_fx8.value = y;
                    moved += 1;
                }
            }
            if moved > 0 {
                report.push(format!(
                    "{name}: {moved} things moved by up to {NUDGE_MAX} units so that their footprint (half the sprite's width across) fits their piece of the map"
                ));
                built = map_build::build(name, source, &catalog);
            }
            let still_out = misfits(&built);
            if !still_out.is_empty() {
                source
                    .things
                    .retain(|thing| !still_out.contains(&convert::thing_of_loc(thing.place.loc)));
                report.push(format!(
                    "{name}: {} things do not fit their piece of the map (a footprint half the sprite's width across, crossing a wall or a cut between pieces, or a sprite through the floor or the ceiling): left out",
                    still_out.len()
                ));
                built = map_build::build(name, source, &catalog);
            }
        }
        match built {
            Ok((mut map, _, fits)) => {
                let found = map_build::finish_things(&mut map, &fits, size);
                errors.extend(
                    found
                        .into_iter()
                        .map(|(_, message)| DoomError::new(wad.path(), Some(name), message)),
                );
                maps.push(map);
            }
            Err(found) => errors.extend(
                found
                    .into_iter()
                    .map(|(_, message)| DoomError::new(wad.path(), Some(name), message)),
            ),
        }
    }
    if !errors.is_empty() {
        if request.maps.is_none() {
            let built: Vec<&str> = maps.iter().map(|map| map.name.as_str()).collect();
            errors.push(DoomError::new(
                wad.path(),
                None,
                format!(
                    "not every map of the WAD can be built; pick maps with PORTALCAST_MAPS (these build: {})",
                    built.join(",")
                ),
            ));
        }
        return Err(errors);
    }
    maps.sort_by(|a, b| a.name.cmp(&b.name));

    let usage = Usage::of(&maps, &catalog);
    let doom_palette = graphics::palette(&graphics_wad)
        .map(|rgb| DoomPalette::new(&rgb))
        .map_err(one)?;
    let doom_rows = graphics::colormaps(&graphics_wad).map_err(one)?;
    let mut quantiser = Quantiser::fixed(doom_palette.palette);
    // The first map using each catalog texture, for errors.
    let first_user = |index: usize| {
        maps.iter()
            .find(|map| {
                let uses = |texture: u16| usize::from(texture) == index;
                map.walls.iter().any(|wall| {
                    uses(wall.texture) || uses(wall.upper_texture) || uses(wall.lower_texture)
                }) || map
                    .sectors
                    .iter()
                    .any(|sector| uses(sector.floor_texture) || uses(sector.ceil_texture))
            })
            .map_or("?", |map| map.name.as_str())
    };
    let mut texture_index = vec![NO_TEXTURE; catalog.textures().len()];
    let mut textures = Vec::new();
    for (index, name) in catalog.textures().iter().enumerate() {
        let (wall, flat) = (usage.wall_textures[index], usage.flat_textures[index]);
        if !wall && !flat {
            continue;
        }
        let image = if let Some(flat_name) = name.strip_prefix(FLAT_PREFIX) {
            graphics::flat(&graphics_wad, flat_name)
        } else if name == STAND_IN_TEXTURE {
            Ok(IndexedImage {
                width: 8,
                height: 8,
                texels: vec![Some(0); 64],
            })
        } else {
            wall_textures.compose(&graphics_wad, name)
        };
        let image = match image {
            Ok(image) => image,
            Err(error) => {
                errors.push(used_by(error, first_user(index)));
                continue;
            }
        };
        let (width, height) = if flat {
            // Floors and ceilings need a square (Doom's flats all are).
            let side = texture_side(image.width.max(image.height));
            (side, side)
        } else {
            (texture_side(image.width), texture_side(image.height))
        };
        if (width, height) != (u32::from(image.width), u32::from(image.height)) {
            report.push(format!(
                "texture {name} is {}x{}: stored {width}x{height}, repeated to fill (or cut)",
                image.width, image.height
            ));
        }
        let rgba = picture(&image, width, height, &doom_palette, &quantiser);
        let (columns, rows) = texels::texture_chains(&rgba, wall, flat, &mut quantiser);
        texture_index[index] = textures.len() as u16;
        textures.push(CompiledTexture {
            name: name.clone(),
            width_log2: width.trailing_zeros() as u8,
            height_log2: height.trailing_zeros() as u8,
            mip_count: texels::mip_count(width, height),
            columns,
            rows,
        });
    }
    let sky = if usage.sky {
        let first = &maps[0].name;
        let name = sky_texture(first);
        match wall_textures.compose(&graphics_wad, &name) {
            Ok(image) => {
                let height = u32::from(image.height)
                    .next_power_of_two()
                    .clamp(SKY_HEIGHT_MIN, SKY_HEIGHT_MAX);
                // Doom repeats its sky texture round the turn every 1024 / width columns.
                let repeats = (DOOM_SKY_COLUMNS_PER_TURN / u32::from(image.width).max(1)).max(1);
                let width = (texture_side(image.width) * repeats)
                    .next_power_of_two()
                    .min(SKY_WIDTH_MAX);
                let rgba = picture(&image, width, height, &doom_palette, &quantiser);
                if names.iter().any(|map| sky_texture(map) != name) {
                    report.push(format!(
                        "the ROM has one sky: every map shows {name}, {first}'s"
                    ));
                }
                Some(CompiledSky {
                    width_log2: width.trailing_zeros() as u8,
                    height: height as u16,
                    texels: texels::sky_columns(&rgba, &mut quantiser),
                })
            }
            Err(error) => {
                errors.push(used_by(error, first));
                None
            }
        }
    } else {
        None
    };
    if !errors.is_empty() {
        return Err(errors);
    }
    let mut set_index = vec![0u16; catalog.sprite_sets().len()];
    let mut sprite_sets = Vec::new();
    let mut sprites = Vec::new();
    for (old, set_name) in catalog.sprite_sets().iter().enumerate() {
        let Some(set) = sets.get(set_name).filter(|_| usage.sprites[old]) else {
            continue;
        };
        set_index[old] = sprite_sets.len() as u16;
        sprite_sets.push(CompiledSpriteSet {
            name: set_name.clone(),
            first: sprites.len() as u16,
            frames: set.frames,
            rotations: set.rotations,
        });
        let naming = SetSource {
            name: set_name.clone(),
            frames: set.frames,
            rotations: set.rotations,
            files: Vec::new(),
            file_names: Vec::new(),
        };
        for (index, image) in set.images.iter().enumerate() {
            let rgba = sprite_picture(image, &doom_palette, &quantiser);
            sprites.push(CompiledSprite {
                name: naming.image_name(index),
                width: image.width,
                height: image.height,
                posts: texels::sprite_columns(&rgba, &mut quantiser),
            });
        }
    }
    crate::renumber(&mut maps, &texture_index, &set_index);
    Ok(Compiled {
        source_dir: request.wad.clone(),
        files_read,
        palette: doom_palette.palette,
        colormap: colormap(&doom_rows, &doom_palette),
        textures,
        sky,
        sprites,
        sprite_sets,
        maps,
        left_out: Vec::new(),
        import_report: report,
        blend: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skies_follow_doom_s_episodes_and_map_numbers() {
        for (map, sky) in [
            ("E1M1", "SKY1"),
            ("E3M9", "SKY3"),
            ("E4M2", "SKY4"),
            ("MAP01", "SKY1"),
            ("MAP11", "SKY1"),
            ("MAP12", "SKY2"),
            ("MAP20", "SKY2"),
            ("MAP21", "SKY3"),
            ("MAP32", "SKY3"),
        ] {
            assert_eq!(sky_texture(map), sky, "{map}");
        }
    }

    #[test]
    fn texture_sides_become_powers_of_two_within_the_limits() {
        for (side, stored) in [
            (1, 8),
            (8, 8),
            (56, 64),
            (64, 64),
            (72, 128),
            (128, 128),
            (300, 256),
        ] {
            assert_eq!(texture_side(side), stored, "{side}");
        }
    }

    #[test]
    fn the_colormap_darkens_by_two_doom_rows_a_row_and_never_brightens() {
        let rgb: [[u8; 3]; 256] = std::array::from_fn(|i| [i as u8; 3]);
        let palette = DoomPalette::new(&rgb);
        // Doom's row k maps every index to k (a recognisable table).
        let doom_rows: Vec<[u8; 256]> = (0..34).map(|k| [k as u8; 256]).collect();
        let map = colormap(&doom_rows, &palette);
        for index in 1..256 {
            assert_eq!(map[16][index], index as u8);
            assert_eq!(map[31][index], index as u8);
            assert_eq!(map[15][index], 2);
            assert_eq!(map[8][index], 16);
            assert_eq!(map[1][index], 30);
            assert_eq!(map[0][index], 31);
        }
    }
}
