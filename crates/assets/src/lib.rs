//! The portalcast asset compiler. One implementation, used by the ROM's `build.rs`, by a game's
//! own `build.rs` through [`Builder`], and by host tests.
//!
//! [`compile_dir`] reads an asset directory (the repo's `assets/` or a user's), checks every map
//! and every image the maps use, and returns a [`Compiled`] set: palette, colormap, textures
//! with mip chains, sky, sprite images and sets, and map tables, owned in `Vec`s. [`Compiled::write_to`] emits
//! them into `OUT_DIR` as `assets.rs` (Rust statics) plus binary blobs pulled in with
//! `include_bytes!`. Host tests can instead borrow the tables directly
//! ([`Compiled::map`]) and run the engine on a freshly compiled map.
//!
//! The directory layout and both map formats are specified in `docs/MAP_FORMAT.md`. Errors are
//! reported all at once, one line each, `file:line:col: what is wrong, what to do`
//! ([`CompileErrors`]); on any error nothing is written.

mod builder;
mod diag;
pub mod doom;
mod emit;
mod geometry;
mod images;
mod layers;
mod lex;
mod map_build;
mod map_grid;
mod map_text;
pub mod numeric_tables;
mod palette;
mod placement;
mod slopes;
mod source;
mod sprite_sets;
mod texels;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use image::RgbaImage;
use portalcast_format::{
    BlendTable, Colormap, MapTables, Palette, Sky, Sprite, SpriteSet, Texture, NO_TEXTURE, SKY,
    THING_TRANSLUCENT, WALL_MIDDLE_TRANSLUCENT,
};

pub use builder::{
    rom_link_args, BuildError, Builder, ASSETS_FILE, LINKER_SCRIPT, LINKER_SCRIPT_FILE,
    WRAPPED_DIVISION_HELPERS,
};
pub use diag::{CompileErrors, Diagnostic, Loc};
pub use map_build::{wall_length_fx8, Catalog, CompiledMap};

/// Extension of text maps.
pub const TEXT_MAP_EXTENSION: &str = "map";
/// Extension of grid maps.
pub const GRID_MAP_EXTENSION: &str = "grid";
/// Folder of wall and flat textures, inside the asset directory.
pub const TEXTURES_DIR: &str = "textures";
/// Folder of sprite images (sprite sets: `NAME.png`, or animation frames and rotations).
pub const SPRITES_DIR: &str = "sprites";
/// Most sprite images the maps' sets may hold in all: a set's first image is a `u16` index.
const SPRITE_IMAGES_MAX: usize = u16::MAX as usize + 1;
/// Folder of the sky panorama.
pub const SKY_DIR: &str = "sky";
/// The sky panorama's file name inside [`SKY_DIR`].
pub const SKY_FILE: &str = "sky.png";
/// Folder of maps.
pub const MAPS_DIR: &str = "maps";

/// A texture compiled for the ROM, owning its texels.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CompiledTexture {
    /// File name without extension.
    pub name: String,
    /// log2 of the width.
    pub width_log2: u8,
    /// log2 of the height.
    pub height_log2: u8,
    /// Mip levels, level 0 included.
    pub mip_count: u8,
    /// Column-major chain (empty unless a wall uses the texture).
    pub columns: Vec<u8>,
    /// Row-major chain (empty unless a floor or ceiling uses the texture).
    pub rows: Vec<u8>,
}

impl CompiledTexture {
    /// The texture as the ROM sees it.
    pub fn texture(&self) -> Texture<'_> {
        Texture {
            name: &self.name,
            width_log2: self.width_log2,
            height_log2: self.height_log2,
            mip_count: self.mip_count,
            columns: &self.columns,
            rows: &self.rows,
        }
    }

    /// Bytes its texels take in the ROM's texel blob: both layouts, each padded to a word.
    pub fn blob_bytes(&self) -> usize {
        self.columns.len().next_multiple_of(4) + self.rows.len().next_multiple_of(4)
    }
}

/// The sky panorama compiled for the ROM.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CompiledSky {
    /// log2 of the width (one full turn).
    pub width_log2: u8,
    /// Height in texels.
    pub height: u16,
    /// Column-major palette indices.
    pub texels: Vec<u8>,
}

impl CompiledSky {
    /// The sky as the ROM sees it.
    pub fn sky(&self) -> Sky<'_> {
        Sky {
            width_log2: self.width_log2,
            height: self.height,
            texels: &self.texels,
        }
    }
}

/// A sprite image compiled for the ROM.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CompiledSprite {
    /// Its set's name, then `.K` (frame K, from 1) if the set is animated, then `.rR` if it has
    /// rotations: `torch`, `flame.3`, `statue.r5`, `knight.2.r0` (a strip's frames are named as
    /// if they were separate files).
    pub name: String,
    /// Width in texels.
    pub width: u16,
    /// Height in texels.
    pub height: u16,
    /// The columns' posts ([`Sprite::posts`]).
    pub posts: Vec<u8>,
}

impl CompiledSprite {
    /// The sprite as the ROM sees it.
    pub fn sprite(&self) -> Sprite<'_> {
        Sprite {
            name: &self.name,
            width: self.width,
            height: self.height,
            posts: &self.posts,
        }
    }
}

/// A sprite set compiled for the ROM: its images are
/// [`Compiled::sprites`]`[first + frame·rotations + rotation]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CompiledSpriteSet {
    /// The set's name, as things give it.
    pub name: String,
    /// Index of its first image in [`Compiled::sprites`].
    pub first: u16,
    /// Animation frames (1: still).
    pub frames: u8,
    /// 1, or 8 (rotation `r` is the thing seen from the direction facing + r·45°).
    pub rotations: u8,
}

impl CompiledSpriteSet {
    /// The set as the ROM sees it.
    pub fn set(&self) -> SpriteSet<'_> {
        SpriteSet {
            name: &self.name,
            first: self.first,
            frames: self.frames,
            rotations: self.rotations,
        }
    }
}

/// A compiled asset set: everything the maps use, and nothing else.
#[derive(Clone, Debug)]
pub struct Compiled {
    source_dir: PathBuf,
    files_read: Vec<PathBuf>,
    palette: Palette,
    colormap: Box<Colormap>,
    textures: Vec<CompiledTexture>,
    sky: Option<CompiledSky>,
    sprites: Vec<CompiledSprite>,
    sprite_sets: Vec<CompiledSpriteSet>,
    maps: Vec<CompiledMap>,
    left_out: Vec<String>,
    import_report: Vec<String>,
    blend: Option<Box<BlendTable>>,
}

impl Compiled {
    /// The shared BGR555 palette; entry 0 is transparent.
    pub fn palette(&self) -> &Palette {
        &self.palette
    }

    /// The light colormap.
    pub fn colormap(&self) -> &Colormap {
        &self.colormap
    }

    /// The 50 % blend table (`blend[behind][front]`), if some map draws something translucent (a
    /// wall middle or a thing); else `None`, and the ROM ships none.
    ///
    /// `blend[0][0]` is 0 (transparent); every other entry is an opaque index (1..=255) whose
    /// shown colour is nearest (squared RGB distance, as the colormap's) to the rounded average
    /// of the two entries' shown colours, index 0 counting as black, the colour the GBA shows for
    /// it. The table is symmetric, and `blend[a][a] == a`.
    pub fn blend(&self) -> Option<&BlendTable> {
        self.blend.as_deref()
    }

    /// Textures used by some map, sorted by name; walls and sectors index this list.
    pub fn textures(&self) -> &[CompiledTexture] {
        &self.textures
    }

    /// The game's live map state the ROM makes room for: the sectors of the largest map with
    /// movers or light effects (0: none has either), the most movers and the most triggers a
    /// map has.
    pub fn live_counts(&self) -> (usize, usize, usize) {
        let most =
            |count: fn(&CompiledMap) -> usize| self.maps.iter().map(count).max().unwrap_or(0);
        (
            most(|map| {
                if map.movers.is_empty() && map.lights.is_empty() {
                    0
                } else {
                    map.sectors.len()
                }
            }),
            most(|map| map.movers.len()),
            most(|map| map.triggers.len()),
        )
    }

    /// EWRAM bytes of the live map state ([`Compiled::live_counts`]), which textures' EWRAM
    /// copy leaves room for (`portalcast_format::memory::live_state_bytes`).
    pub fn live_state_bytes(&self) -> usize {
        let (sectors, movers, triggers) = self.live_counts();
        portalcast_format::memory::live_state_bytes(sectors, movers, triggers)
    }

    /// Per texture (in [`Compiled::textures`]' order): whether the ROM copies its texels to
    /// EWRAM. The hottest textures (the most map area) that fit the EWRAM the engine leaves
    /// them (`portalcast_format::memory::ewram_texel_budget`) go; the others are read from the
    /// cartridge.
    pub fn textures_in_ewram(&self) -> Vec<bool> {
        placement::textures_in_ewram(self)
    }

    /// Every texture chain some map uses, as (index in [`Compiled::textures`], chain), the
    /// hottest first (the most map area): the order in which the ROM copies chains to the VRAM
    /// a 120×80 frame leaves free.
    pub fn texture_chains_by_heat(&self) -> Vec<(u16, portalcast_format::TextureChain)> {
        placement::chains_by_heat(self)
    }

    /// The sky, if some sector shows it.
    pub fn sky(&self) -> Option<&CompiledSky> {
        self.sky.as_ref()
    }

    /// The images of the sprite sets, set by set in [`Compiled::sprite_sets`]' order, each
    /// set's frames in order and each frame's rotations in order; sets index this list.
    pub fn sprites(&self) -> &[CompiledSprite] {
        &self.sprites
    }

    /// Sprite sets used by some thing or wall middle, sorted by name; things and walls index
    /// this list ([`portalcast_format::Thing::sprite`], [`portalcast_format::Wall::middle`]).
    pub fn sprite_sets(&self) -> &[CompiledSpriteSet] {
        &self.sprite_sets
    }

    /// All maps, sorted by name.
    pub fn maps(&self) -> &[CompiledMap] {
        &self.maps
    }

    /// The tables of the map called `name` (file name without extension).
    pub fn map(&self, name: &str) -> Option<MapTables<'_>> {
        self.maps
            .iter()
            .find(|m| m.name == name)
            .map(CompiledMap::tables)
    }

    /// The tables as a game on the host reads them: [`HostTables::assets`] is the same
    /// [`portalcast_format::Assets`] value a game's generated `ASSETS` is on the GBA, borrowed
    /// from this compilation (for host tests and tools running the engine on a user's assets).
    pub fn host_tables(&self) -> HostTables<'_> {
        HostTables {
            compiled: self,
            textures: self.textures.iter().map(CompiledTexture::texture).collect(),
            chains_by_heat: self.texture_chains_by_heat(),
            sky: self.sky.as_ref().map(CompiledSky::sky),
            sprites: self.sprites.iter().map(CompiledSprite::sprite).collect(),
            sprite_sets: self
                .sprite_sets
                .iter()
                .map(CompiledSpriteSet::set)
                .collect(),
            maps: self.maps.iter().map(CompiledMap::tables).collect(),
        }
    }

    /// Files and folders the compilation read: print each as `cargo:rerun-if-changed`.
    pub fn files_read(&self) -> &[PathBuf] {
        &self.files_read
    }

    /// Assets present in the directory but used by no map, hence left out.
    pub fn left_out(&self) -> &[String] {
        &self.left_out
    }

    /// What an import from a Doom WAD could not map (unsupported specials, closed sectors,
    /// missing textures, things), one line each; empty for an asset directory.
    pub fn import_report(&self) -> &[String] {
        &self.import_report
    }

    /// Writes `assets.rs` and its blobs into `out_dir` (each to a temporary name first, renamed
    /// into place once all are written). Returns the files the compilation read, for
    /// `cargo:rerun-if-changed`.
    pub fn write_to(&self, out_dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        emit::write(self, out_dir)?;
        Ok(self.files_read.clone())
    }

    /// ROM bytes per asset kind, and the RAM the tables would need if copied to EWRAM or IWRAM.
    pub fn size_report(&self) -> String {
        emit::size_report(self)
    }
}

/// A compilation's tables, each texture's texels where the compilation keeps them (there is no
/// texel blob on the host, and nothing goes to EWRAM): [`Compiled::host_tables`].
pub struct HostTables<'c> {
    compiled: &'c Compiled,
    textures: Vec<Texture<'c>>,
    chains_by_heat: Vec<(u16, portalcast_format::TextureChain)>,
    sky: Option<Sky<'c>>,
    sprites: Vec<Sprite<'c>>,
    sprite_sets: Vec<SpriteSet<'c>>,
    maps: Vec<MapTables<'c>>,
}

impl HostTables<'_> {
    /// Everything as one value, as the engine takes it.
    pub fn assets(&self) -> portalcast_format::Assets<'_> {
        portalcast_format::Assets {
            palette: &self.compiled.palette,
            colormap: &self.compiled.colormap,
            textures: &self.textures,
            texel_blob: &[],
            texel_ewram_len: 0,
            texture_chains_by_heat: &self.chains_by_heat,
            sky: self.sky,
            blend: self.compiled.blend(),
            sprites: &self.sprites,
            sprite_sets: &self.sprite_sets,
            maps: &self.maps,
        }
    }
}

/// Parses and checks one map from text, against a catalog of texture and sprite set names (no
/// images are read). `file_name` picks the format by extension (`.map` or `.grid`) and names
/// the file in errors. Texture and sprite set indices in the result refer to the catalog's
/// lists. Things are checked against the sprite sizes the catalog knows
/// ([`Catalog::with_sprite_size`]; a set without one counts as 0×0, so its things get radius 0
/// unless `radius=` says more).
pub fn compile_map_str(
    file_name: &str,
    text: &str,
    catalog: &Catalog,
) -> Result<CompiledMap, CompileErrors> {
    let (mut map, _, fits) = compile_map_parts(file_name, text, catalog)?;
    let errors = map_build::finish_things(&mut map, &fits, |sprite| {
        Some(catalog.sprite_size(sprite).unwrap_or((0, 0)))
    });
    if errors.is_empty() {
        Ok(map)
    } else {
        Err(CompileErrors::in_file(Path::new(file_name), errors))
    }
}

/// [`compile_map_str`] before the checks of things against their sprites' sizes: also returns
/// where the map uses each texture as a floor or ceiling, and what those checks need.
fn compile_map_parts(
    file_name: &str,
    text: &str,
    catalog: &Catalog,
) -> Result<
    (
        CompiledMap,
        Vec<map_build::FlatUse>,
        Vec<map_build::ThingFit>,
    ),
    CompileErrors,
> {
    let path = Path::new(file_name);
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("map")
        .to_string();
    // A byte-order mark some editors put first is not part of the map (columns count from
    // after it).
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let parsed = match map_format(path) {
        Some(GRID_MAP_EXTENSION) => map_grid::parse(text),
        Some(TEXT_MAP_EXTENSION) => map_text::parse(text),
        _ => Err(vec![(
            Loc::START,
            format!("unknown map format; name the file *.{TEXT_MAP_EXTENSION} or *.{GRID_MAP_EXTENSION}"),
        )]),
    };
    parsed
        .and_then(|source| map_build::build(&stem, &source, catalog))
        .map_err(|errors| CompileErrors::in_file(path, errors))
}

/// The map format of `path` by its extension, in any case (`ROOM.MAP` is a text map):
/// [`TEXT_MAP_EXTENSION`], [`GRID_MAP_EXTENSION`] or none.
fn map_format(path: &Path) -> Option<&'static str> {
    let extension = path.extension()?.to_str()?;
    [TEXT_MAP_EXTENSION, GRID_MAP_EXTENSION]
        .into_iter()
        .find(|known| extension.eq_ignore_ascii_case(known))
}

/// Where the first byte that is not UTF-8 lies in `bytes` (1-based line and character column),
/// and the byte.
fn first_bad_byte(bytes: &[u8], error: &std::str::Utf8Error) -> (Loc, u8) {
    let valid = &bytes[..error.valid_up_to()];
    // The prefix is valid UTF-8 by the error's own account.
    let text = std::str::from_utf8(valid).unwrap_or_default();
    let line = text.matches('\n').count() + 1;
    let column = text.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    let loc = Loc::new(
        u32::try_from(line).unwrap_or(u32::MAX),
        u32::try_from(column).unwrap_or(u32::MAX),
    );
    (loc, bytes[error.valid_up_to()])
}

/// Names of the `*.png` files of a folder (missing folder: none), with their paths.
fn png_files(dir: &Path) -> BTreeMap<String, PathBuf> {
    let mut found = BTreeMap::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return found;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let is_png = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("png"));
        if let (true, Some(stem)) = (is_png, path.file_stem().and_then(|s| s.to_str())) {
            found.insert(stem.to_string(), path);
        }
    }
    found
}

/// What the maps use, by catalog index.
#[derive(Default)]
struct Usage {
    wall_textures: Vec<bool>,
    flat_textures: Vec<bool>,
    /// By sprite set: things' and wall middles'.
    sprites: Vec<bool>,
    sky: bool,
    /// Some wall middle or thing is drawn translucent: the ROM needs the blend table.
    translucent: bool,
}

impl Usage {
    fn of(maps: &[CompiledMap], catalog: &Catalog) -> Usage {
        let mut usage = Usage {
            wall_textures: vec![false; catalog.textures().len()],
            flat_textures: vec![false; catalog.textures().len()],
            sprites: vec![false; catalog.sprite_sets().len()],
            sky: false,
            translucent: false,
        };
        for map in maps {
            for wall in &map.walls {
                for texture in [wall.texture, wall.upper_texture, wall.lower_texture] {
                    if texture != NO_TEXTURE {
                        usage.wall_textures[usize::from(texture)] = true;
                    }
                }
                if wall.middle != NO_TEXTURE {
                    usage.sprites[usize::from(wall.middle)] = true;
                }
                usage.translucent |= wall.flags & WALL_MIDDLE_TRANSLUCENT != 0;
            }
            // A switch shows its used texture on its (solid) wall once used.
            for trigger in &map.triggers {
                if trigger.used_texture != NO_TEXTURE {
                    usage.wall_textures[usize::from(trigger.used_texture)] = true;
                }
            }
            for sector in &map.sectors {
                usage.flat_textures[usize::from(sector.floor_texture)] = true;
                if sector.ceil_texture == SKY {
                    usage.sky = true;
                } else {
                    usage.flat_textures[usize::from(sector.ceil_texture)] = true;
                }
            }
            for thing in &map.things {
                usage.sprites[usize::from(thing.sprite)] = true;
                usage.translucent |= thing.flags & THING_TRANSLUCENT != 0;
            }
        }
        usage
    }
}

/// Renumbers the maps' textures and sprite sets from the catalog's indices to the compiled
/// lists': `texture_index` and `set_index` give each catalog entry's new index.
fn renumber(maps: &mut [CompiledMap], texture_index: &[u16], set_index: &[u16]) {
    let remap = |texture: u16| match texture {
        NO_TEXTURE | SKY => texture,
        other => texture_index[usize::from(other)],
    };
    for map in maps {
        for wall in &mut map.walls {
            wall.texture = remap(wall.texture);
            wall.upper_texture = remap(wall.upper_texture);
            wall.lower_texture = remap(wall.lower_texture);
            if wall.middle != NO_TEXTURE {
                wall.middle = set_index[usize::from(wall.middle)];
            }
        }
        for trigger in &mut map.triggers {
            trigger.used_texture = remap(trigger.used_texture);
        }
        for sector in &mut map.sectors {
            sector.floor_texture = remap(sector.floor_texture);
            sector.ceil_texture = remap(sector.ceil_texture);
        }
        for thing in &mut map.things {
            thing.sprite = set_index[usize::from(thing.sprite)];
        }
    }
}

/// Refuses a texture used as a floor or ceiling unless it is square: the span kernels (and
/// their host twins) index a flat as a `side × side` tile, so a 32×64 flat would be read past
/// its texels (`FLAT_LOG2_SIDES` in `src/raster/flat.rs`). Each use is reported where the map
/// names the texture. Walls take any power-of-two rectangle.
fn check_flat_shapes(
    texture_images: &[(usize, &String, Option<RgbaImage>)],
    flat_uses: &[(&Path, map_build::FlatUse)],
    errors: &mut Vec<Diagnostic>,
) {
    for (map_path, used) in flat_uses {
        let Some((_, name, Some(image))) = texture_images
            .iter()
            .find(|(index, _, _)| *index == usize::from(used.texture))
        else {
            continue;
        };
        let (width, height) = image.dimensions();
        if width == height {
            continue;
        }
        let side = width.min(height);
        errors.push(Diagnostic::new(
            map_path,
            (
                used.loc,
                format!(
                    "{} texture '{name}' is {width}x{height}; floors and ceilings need a square texture: resize {TEXTURES_DIR}/{name}.png to {side}x{side} (or another square power of two), or use a square texture here",
                    used.what
                ),
            ),
        ));
    }
}

/// Compiles the asset directory `dir`: `textures/*.png`, `sprites/*.png` (sprite sets),
/// `sky/sky.png` and `maps/*.map`, `maps/*.grid` (see `docs/MAP_FORMAT.md`). Only what some map
/// uses is kept. Returns every error found, sorted by file and position.
pub fn compile_dir(dir: &Path) -> Result<Compiled, CompileErrors> {
    compile_selected(dir, None)
}

/// [`compile_dir`] with only the maps named in `maps` (file names without extension, in any
/// case; `PORTALCAST_MAPS`), and only what they use. A name no map file has is an error that
/// lists the maps there are.
pub fn compile_dir_maps(dir: &Path, maps: &[String]) -> Result<Compiled, CompileErrors> {
    compile_selected(dir, Some(maps))
}

fn compile_selected(dir: &Path, selected: Option<&[String]>) -> Result<Compiled, CompileErrors> {
    if !dir.is_dir() {
        let what = if dir.exists() {
            "is not a directory"
        } else {
            "does not exist"
        };
        return Err(CompileErrors(vec![Diagnostic::new(
            dir,
            (
                Loc::START,
                format!("the asset directory {what}; check the path (PORTALCAST_ASSETS, if set) or create it with {MAPS_DIR}/ and {TEXTURES_DIR}/ inside"),
            ),
        )]));
    }
    let mut errors: Vec<Diagnostic> = Vec::new();
    let mut files_read = vec![dir.to_path_buf()];
    let textures_dir = dir.join(TEXTURES_DIR);
    let sprites_dir = dir.join(SPRITES_DIR);
    let sky_path = dir.join(SKY_DIR).join(SKY_FILE);
    let maps_dir = dir.join(MAPS_DIR);
    let texture_files = png_files(&textures_dir);
    let (set_sources, set_errors) = sprite_sets::scan(&png_files(&sprites_dir));
    errors.extend(set_errors);
    let mut catalog = Catalog::new(
        texture_files.keys().cloned(),
        set_sources.iter().map(|set| set.name.clone()),
        sky_path.is_file(),
    );
    for set in &set_sources {
        catalog = catalog.with_sprite_frames(&set.name, set.frames, set.rotations);
    }
    if catalog.textures().len() >= usize::from(SKY) {
        errors.push(Diagnostic::new(
            &textures_dir,
            (
                Loc::START,
                format!(
                    "{} textures are more than the tables can index; remove some",
                    catalog.textures().len()
                ),
            ),
        ));
    }

    let mut map_files: Vec<PathBuf> = std::fs::read_dir(&maps_dir)
        .map(|entries| {
            entries
                .flatten()
                .map(|e| e.path())
                .filter(|p| map_format(p).is_some())
                .collect()
        })
        .unwrap_or_default();
    map_files.sort();
    if let Some(selected) = selected {
        let stem = |path: &PathBuf| {
            path.file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or_default()
                .to_ascii_lowercase()
        };
        for name in selected {
            if !map_files
                .iter()
                .any(|path| stem(path) == name.to_ascii_lowercase())
            {
                let present: Vec<String> = map_files.iter().map(stem).collect();
                errors.push(Diagnostic::new(
                    &maps_dir,
                    (
                        Loc::START,
                        format!(
                            "no map called '{name}' (PORTALCAST_MAPS); the maps here are {}",
                            present.join(", ")
                        ),
                    ),
                ));
            }
        }
        map_files.retain(|path| {
            selected
                .iter()
                .any(|name| stem(path) == name.to_ascii_lowercase())
        });
    }
    if !maps_dir.is_dir() {
        errors.push(Diagnostic::new(
            &maps_dir,
            (Loc::START, format!("the asset directory has no {MAPS_DIR} folder; create it and put at least one *.{TEXT_MAP_EXTENSION} or *.{GRID_MAP_EXTENSION} file in it")),
        ));
    } else if map_files.is_empty() {
        errors.push(Diagnostic::new(
            &maps_dir,
            (Loc::START, format!("no maps found; add at least one *.{TEXT_MAP_EXTENSION} or *.{GRID_MAP_EXTENSION} file to this folder")),
        ));
    }

    let mut maps: Vec<CompiledMap> = Vec::new();
    // Each map's floor and ceiling textures with their places, checked once the images load.
    let mut flat_uses: Vec<(&Path, map_build::FlatUse)> = Vec::new();
    // Per map (in `maps`' order), its things' checks against their sprites' sizes, done once the
    // sprites load.
    let mut thing_fits: Vec<(&Path, Vec<map_build::ThingFit>)> = Vec::new();
    for path in &map_files {
        files_read.push(path.clone());
        let text = match std::fs::read(path).map(String::from_utf8) {
            Ok(Ok(text)) => text,
            Ok(Err(error)) => {
                let (loc, byte) = first_bad_byte(error.as_bytes(), &error.utf8_error());
                errors.push(Diagnostic::new(
                    path,
                    (
                        loc,
                        format!("byte 0x{byte:02X} is not UTF-8 text; save the file as UTF-8 (or remove the character here)"),
                    ),
                ));
                continue;
            }
            Err(e) => {
                errors.push(Diagnostic::new(
                    path,
                    (Loc::START, format!("cannot read the file ({e})")),
                ));
                continue;
            }
        };
        match compile_map_parts(&path.to_string_lossy(), &text, &catalog) {
            Ok((map, uses, fits)) => {
                flat_uses.extend(uses.into_iter().map(|used| (path.as_path(), used)));
                if let Some(first) = maps.iter().find(|m| m.name == map.name) {
                    errors.push(Diagnostic::new(
                        path,
                        (
                            Loc::START,
                            format!(
                                "another map is also called '{}'; rename one of the files",
                                first.name
                            ),
                        ),
                    ));
                } else {
                    maps.push(map);
                    thing_fits.push((path.as_path(), fits));
                }
            }
            Err(CompileErrors(found)) => errors.extend(found),
        }
    }

    let usage = Usage::of(&maps, &catalog);
    let mut load =
        |path: &Path, check: fn(&RgbaImage) -> Vec<diag::Located>, errors: &mut Vec<Diagnostic>| {
            files_read.push(path.to_path_buf());
            match images::load(path) {
                Ok(image) => {
                    let found = check(&image);
                    let ok = found.is_empty();
                    errors.extend(found.into_iter().map(|e| Diagnostic::new(path, e)));
                    ok.then_some(image)
                }
                Err(e) => {
                    errors.push(Diagnostic::new(path, e));
                    None
                }
            }
        };
    let mut texture_images = Vec::new();
    let mut left_out = Vec::new();
    for (index, (name, path)) in texture_files.iter().enumerate() {
        if usage.wall_textures[index] || usage.flat_textures[index] {
            texture_images.push((index, name, load(path, images::check_texture, &mut errors)));
        } else {
            left_out.push(format!("{TEXTURES_DIR}/{name}.png"));
        }
    }
    // The used sets (by catalog index) with their images, if they all loaded and passed
    // their checks.
    let mut set_images = Vec::new();
    // Width and height of each set's images (by catalog index), where known.
    let mut sprite_sizes = vec![None; catalog.sprite_sets().len()];
    let mut image_count = 0;
    // The sprite files read (`load` holds `files_read` until the sky is loaded).
    let mut sprite_files_read = Vec::new();
    for (index, set) in set_sources.iter().enumerate() {
        if usage.sprites[index] {
            image_count += set.image_count();
            let images = sprite_sets::load(set, &mut sprite_files_read, &mut errors);
            sprite_sizes[index] = images
                .as_ref()
                .map(|images| (images[0].width() as u16, images[0].height() as u16));
            set_images.push((set, images));
        } else {
            left_out.extend(set.file_names.iter().cloned());
        }
    }
    if image_count > SPRITE_IMAGES_MAX {
        errors.push(Diagnostic::new(
            &sprites_dir,
            (
                Loc::START,
                format!(
                    "the sprite sets the maps use hold {image_count} images, more than the {SPRITE_IMAGES_MAX} the sprite table can index; use fewer frames or rotations"
                ),
            ),
        ));
    }
    for (map, (path, fits)) in maps.iter_mut().zip(&thing_fits) {
        let found = map_build::finish_things(map, fits, |sprite| {
            sprite_sizes.get(usize::from(sprite)).copied().flatten()
        });
        errors.extend(found.into_iter().map(|e| Diagnostic::new(path, e)));
    }
    check_flat_shapes(&texture_images, &flat_uses, &mut errors);
    let sky_image = if usage.sky {
        load(&sky_path, images::check_sky, &mut errors)
    } else {
        if catalog.has_sky() {
            left_out.push(format!("{SKY_DIR}/{SKY_FILE}"));
        }
        None
    };
    files_read.extend(sprite_files_read);
    if !errors.is_empty() {
        return Err(CompileErrors::sorted(errors));
    }

    // Every image loaded and passed its checks (else errors is not empty).
    let texture_images: Vec<(usize, &String, RgbaImage)> = texture_images
        .into_iter()
        .filter_map(|(i, n, image)| Some((i, n, image?)))
        .collect();
    let set_images: Vec<(&sprite_sets::SetSource, Vec<RgbaImage>)> = set_images
        .into_iter()
        .filter_map(|(set, images)| Some((set, images?)))
        .collect();

    let mut samples = Vec::new();
    for (_, _, image) in &texture_images {
        texels::opaque_samples(image, &mut samples);
    }
    if let Some(image) = &sky_image {
        texels::opaque_samples(image, &mut samples);
    }
    for image in set_images.iter().flat_map(|(_, images)| images) {
        texels::opaque_samples(image, &mut samples);
    }
    let mut quantiser = palette::Quantiser::new(&samples);

    let mut texture_index = vec![NO_TEXTURE; catalog.textures().len()];
    let mut textures = Vec::new();
    for (old, name, image) in &texture_images {
        texture_index[*old] = textures.len() as u16;
        let (columns, rows) = texels::texture_chains(
            image,
            usage.wall_textures[*old],
            usage.flat_textures[*old],
            &mut quantiser,
        );
        textures.push(CompiledTexture {
            name: (*name).clone(),
            width_log2: image.width().trailing_zeros() as u8,
            height_log2: image.height().trailing_zeros() as u8,
            mip_count: texels::mip_count(image.width(), image.height()),
            columns,
            rows,
        });
    }
    let mut set_index = vec![0u16; catalog.sprite_sets().len()];
    let mut sprite_sets = Vec::new();
    let mut sprites = Vec::new();
    for (set, images) in &set_images {
        if let Ok(old) = catalog.sprite_sets().binary_search(&set.name) {
            set_index[old] = sprite_sets.len() as u16;
        }
        sprite_sets.push(CompiledSpriteSet {
            name: set.name.clone(),
            // At most SPRITE_IMAGES_MAX images in all (checked above).
            first: sprites.len() as u16,
            frames: set.frames,
            rotations: set.rotations,
        });
        for (image_index, image) in images.iter().enumerate() {
            sprites.push(CompiledSprite {
                name: set.image_name(image_index),
                width: image.width() as u16,
                height: image.height() as u16,
                posts: texels::sprite_columns(image, &mut quantiser),
            });
        }
    }
    let sky = sky_image.map(|image| CompiledSky {
        width_log2: image.width().trailing_zeros() as u8,
        height: image.height() as u16,
        texels: texels::sky_columns(&image, &mut quantiser),
    });
    renumber(&mut maps, &texture_index, &set_index);
    files_read.extend([textures_dir, sprites_dir, dir.join(SKY_DIR), maps_dir]);
    // Cargo reruns a build script on every build if a watched path does not exist; the asset
    // directory itself is watched recursively, so a folder created later is still noticed.
    files_read.retain(|path| path.exists());
    files_read.sort();
    files_read.dedup();
    Ok(Compiled {
        source_dir: dir.to_path_buf(),
        files_read,
        palette: quantiser.palette(),
        colormap: quantiser.colormap(),
        blend: usage.translucent.then(|| quantiser.blend()),
        textures,
        sky,
        sprites,
        sprite_sets,
        maps,
        left_out,
        import_report: Vec::new(),
    })
}
