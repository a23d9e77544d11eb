//! The `.map` text format (specified in `docs/MAP_FORMAT.md`): vertices, sectors with their
//! walls, the player start and things, one directive per line.

use std::collections::hash_map::Entry;
use std::collections::HashMap;

use portalcast_format::PlayerSize;

use crate::diag::{Loc, Located};
use crate::lex::{self, KeyValues, Token};
use crate::source::{
    CeilingSource, SourceMap, SourcePlace, SourceSector, SourceSlope, SourceThing, SourceVertex,
    SourceWall, Spanned,
};

/// Highest `layer=`.
const LAYER_MAX: i64 = 15;

/// Light level of a sector that does not set `light=`: textures shown as painted.
const DEFAULT_LIGHT: u8 = portalcast_format::LIGHT_NEUTRAL;

const SECTOR_KEYS: &[&str] = &[
    "floor",
    "ceil",
    "floor_slope",
    "ceil_slope",
    "floor_tex",
    "ceil_tex",
    "light",
    "lift",
    "platform",
    "crusher",
    "speed",
    "wait",
    "tag",
    "glow",
    "strobe",
    "flicker",
    "switched",
    "period",
    "layer",
    "ceil_portal",
    "floor_portal",
];
const WALL_KEYS: &[&str] = &[
    "tex", "portal", "upper", "lower", "mid", "switch", "tag", "trigger", "xoff", "yoff",
];
const PLAYER_KEYS: &[&str] = &["angle", "eye", "height", "step", "layer"];
const THING_KEYS: &[&str] = &["angle", "z", "radius", "anim", "layer"];

/// A wall as written: vertex and sector names not yet resolved.
struct WrittenWall<'t> {
    loc: Loc,
    start: Token<'t>,
    end: Token<'t>,
    texture: Option<Spanned<String>>,
    portal: Option<Token<'t>>,
    upper: Option<Spanned<String>>,
    lower: Option<Spanned<String>>,
    x_offset: Spanned<i64>,
    y_offset: Spanned<i64>,
    middle: Option<Spanned<String>>,
    blocks: Option<Loc>,
    translucent: Option<Loc>,
    switch: Option<Spanned<String>>,
    tag: Option<Spanned<u16>>,
    trigger: Option<Spanned<u16>>,
}

struct WrittenSector<'t> {
    sector: SourceSector,
    walls: Vec<WrittenWall<'t>>,
    /// `floor_slope=` and `ceil_slope=` as written: vertex names not yet resolved.
    slopes: [Option<WrittenSlope<'t>>; 2],
    /// `ceil_portal=` and `floor_portal=` as written: sector names not yet resolved.
    links: [Option<Token<'t>>; 2],
}

/// A slope's value as written: `NAME:HEIGHT` pairs, vertex names not yet resolved.
struct WrittenSlope<'t> {
    loc: Loc,
    points: Vec<(Token<'t>, Spanned<i64>)>,
}

/// Parses a `.map` file. Reports every syntax and name error it finds.
pub(crate) fn parse(text: &str) -> Result<SourceMap, Vec<Located>> {
    let mut errors = Vec::new();
    let mut vertices: Vec<SourceVertex> = Vec::new();
    let mut vertex_names: HashMap<String, usize> = HashMap::new();
    let mut sectors: Vec<WrittenSector<'_>> = Vec::new();
    let mut sector_names: HashMap<String, usize> = HashMap::new();
    let mut player: Option<SourcePlace> = None;
    let mut player_seen = false;
    let mut player_size = PlayerSize::NATIVE;
    let mut things = Vec::new();

    for (index, raw_line) in text.lines().enumerate() {
        let line_no = u32::try_from(index + 1).unwrap_or(u32::MAX);
        let line = raw_line.split('#').next().unwrap_or("");
        let words = lex::tokens(line, line_no);
        let Some((&directive, rest)) = words.split_first() else {
            continue;
        };
        let (rest, flags) = match directive.text {
            "thing" => {
                lex::split_flags(rest, 3, lex::THING_FLAGS, "thing", THING_KEYS, &mut errors)
            }
            "wall" => lex::split_flags(rest, 2, lex::WALL_FLAGS, "wall", WALL_KEYS, &mut errors),
            "sector" => lex::split_flags(
                rest,
                1,
                lex::SECTOR_FLAGS,
                "sector",
                SECTOR_KEYS,
                &mut errors,
            ),
            _ => (rest.to_vec(), Vec::new()),
        };
        let (positional, mut keys) = KeyValues::split(&rest, &mut errors);
        match directive.text {
            "vertex" => {
                keys.report_unknown("vertex", &[], &mut errors);
                let Some([name, x, y]) =
                    expect_words(directive, &positional, ["NAME", "X", "Y"], &mut errors)
                else {
                    continue;
                };
                let Some(label) = record(lex::name(name, "vertex name"), &mut errors) else {
                    continue;
                };
                let x = record(lex::integer(x, "vertex x"), &mut errors);
                let y = record(lex::integer(y, "vertex y"), &mut errors);
                if vertex_names.contains_key(&label) {
                    errors.push((
                        name.loc,
                        format!("vertex '{label}' is declared twice; rename one"),
                    ));
                    continue;
                }
                vertex_names.insert(label.clone(), vertices.len());
                // A vertex with a bad coordinate keeps its name, so walls using it report
                // nothing more; the map has errors and is not built.
                vertices.push(SourceVertex {
                    label: format!("vertex '{label}'"),
                    x: Spanned::new(x.unwrap_or(0), Loc::new(line_no, positional[1].loc.col)),
                    y: Spanned::new(y.unwrap_or(0), Loc::new(line_no, positional[2].loc.col)),
                });
            }
            "sector" => {
                let (name, parsed, slopes, links) =
                    parse_sector(directive, &positional, &flags, &mut keys, &mut errors);
                keys.report_unknown("sector", SECTOR_KEYS, &mut errors);
                if let Some(name) = name {
                    // A sector with a bad value keeps its name, so portals to it report nothing
                    // more (the bad value is reported; the map is not built).
                    match sector_names.entry(name) {
                        Entry::Occupied(taken) => errors.push((
                            positional[0].loc,
                            format!("sector '{}' is declared twice; rename one", taken.key()),
                        )),
                        Entry::Vacant(free) => {
                            free.insert(sectors.len());
                        }
                    }
                }
                // Without its values, keep later walls attached to something so they are
                // still checked.
                sectors.push(WrittenSector {
                    sector: parsed.unwrap_or_else(|| placeholder_sector(directive.loc)),
                    walls: Vec::new(),
                    slopes,
                    links,
                });
            }
            "wall" => {
                let wall = parse_wall(directive, &positional, &flags, &mut keys, &mut errors);
                keys.report_unknown("wall", WALL_KEYS, &mut errors);
                match (sectors.last_mut(), wall) {
                    (None, _) => errors.push((
                        directive.loc,
                        "wall before any sector; put each sector's walls after its sector line"
                            .to_string(),
                    )),
                    (Some(sector), Some(wall)) => sector.walls.push(wall),
                    (Some(_), None) => {}
                }
            }
            "player" => {
                let place = expect_words(directive, &positional, ["X", "Y"], &mut errors)
                    .and_then(|[x, y]| parse_place(directive, x, y, &mut keys, &mut errors));
                let size = parse_player_size(&mut keys, &mut errors);
                keys.report_unknown("player", PLAYER_KEYS, &mut errors);
                if player_seen {
                    errors.push((
                        directive.loc,
                        "second player start; keep one player line".to_string(),
                    ));
                }
                if !player_seen {
                    player_size = size.unwrap_or(PlayerSize::NATIVE);
                }
                player_seen = true;
                player = player.or(place);
            }
            "thing" => {
                let words = expect_words(directive, &positional, ["SPRITE", "X", "Y"], &mut errors);
                let options = lex::thing_options(&flags, &mut keys, &mut errors);
                let thing = words.and_then(|[sprite, x, y]| {
                    let name = record(lex::name(sprite, "sprite name"), &mut errors);
                    let place = parse_place(directive, x, y, &mut keys, &mut errors)?;
                    Some(SourceThing {
                        sprite: Spanned::new(name?, sprite.loc),
                        place,
                        options: options?,
                    })
                });
                keys.report_unknown("thing", THING_KEYS, &mut errors);
                things.extend(thing);
            }
            other => errors.push((
                directive.loc,
                format!(
                    "unknown directive '{other}'; expected vertex, sector, wall, player or thing"
                ),
            )),
        }
    }

    let sectors = resolve_walls(sectors, &vertex_names, &sector_names, &mut errors);
    match player {
        Some(player) if errors.is_empty() => Ok(SourceMap {
            vertices,
            sectors,
            player,
            player_size,
            things,
        }),
        None if !player_seen => {
            errors.push((
                Loc::START,
                "no player start; add a line `player X Y angle=DEGREES`".to_string(),
            ));
            Err(errors)
        }
        _ => Err(errors),
    }
}

/// Moves a result's error into `errors`.
fn record<T>(result: Result<T, Located>, errors: &mut Vec<Located>) -> Option<T> {
    result.map_err(|e| errors.push(e)).ok()
}

/// Checks that a directive has exactly the positional words `names`.
fn expect_words<'t, const N: usize>(
    directive: Token<'t>,
    words: &[Token<'t>],
    names: [&str; N],
    errors: &mut Vec<Located>,
) -> Option<[Token<'t>; N]> {
    match <[Token<'t>; N]>::try_from(words) {
        Ok(array) => Some(array),
        Err(_) => {
            let at = words.get(N).map_or(directive.loc, |w| w.loc);
            errors.push((
                at,
                format!(
                    "{} takes {} value{} ({}) before its key=value settings, found {}",
                    directive.text,
                    N,
                    if N == 1 { "" } else { "s" },
                    names.join(" "),
                    words.len()
                ),
            ));
            None
        }
    }
}

fn placeholder_sector(loc: Loc) -> SourceSector {
    SourceSector {
        label: String::new(),
        loc,
        floor: Spanned::new(0, loc),
        ceil: Spanned::new(0, loc),
        floor_slope: None,
        ceil_slope: None,
        floor_texture: Spanned::new(String::new(), loc),
        ceiling: CeilingSource::Sky,
        light: DEFAULT_LIGHT,
        mover: None,
        light_effect: None,
        layer: Spanned::new(0, loc),
        above: None,
        below: None,
        walls: Vec::new(),
    }
}

fn texture_name(token: Token<'_>, errors: &mut Vec<Located>) -> Option<Spanned<String>> {
    record(lex::name(token, "texture name"), errors).map(|name| Spanned::new(name, token.loc))
}

/// Parses a `sector` line: its name (if valid) and the sector (if every value is).
#[allow(clippy::type_complexity)]
fn parse_sector<'t>(
    directive: Token<'t>,
    positional: &[Token<'t>],
    flags: &[Token<'t>],
    keys: &mut KeyValues<'t>,
    errors: &mut Vec<Located>,
) -> (
    Option<String>,
    Option<SourceSector>,
    [Option<WrittenSlope<'t>>; 2],
    [Option<Token<'t>>; 2],
) {
    let name = expect_words(directive, positional, ["NAME"], errors)
        .and_then(|[name]| record(lex::name(name, "sector name"), errors));
    let links = [keys.take("ceil_portal"), keys.take("floor_portal")];
    let slopes = [
        keys.take("floor_slope")
            .and_then(|t| parse_slope(t, "floor", errors)),
        keys.take("ceil_slope")
            .and_then(|t| parse_slope(t, "ceiling", errors)),
    ];
    let linked = [links[0].is_some(), links[1].is_some()];
    let sector = parse_sector_values(
        directive,
        name.as_deref(),
        flags,
        keys,
        (&slopes, linked),
        errors,
    );
    (name, sector, slopes, links)
}

/// A `floor_slope=` or `ceil_slope=` value: `NAME:HEIGHT` pairs separated by commas, each
/// part located at its own column.
fn parse_slope<'t>(
    value: Token<'t>,
    what: &str,
    errors: &mut Vec<Located>,
) -> Option<WrittenSlope<'t>> {
    let mut points = Vec::new();
    let mut ok = true;
    let mut offset = 0u32;
    for part in value.text.split(',') {
        let at = Loc::new(value.loc.line, value.loc.col + offset);
        offset += part.chars().count() as u32 + 1;
        let Some((name, height)) = part.split_once(':') else {
            errors.push((
                at,
                format!(
                    "{what} slope point '{part}' needs a vertex and a height: write VERTEX:HEIGHT, e.g. v3:32, and separate the points with commas"
                ),
            ));
            ok = false;
            continue;
        };
        let name = Token {
            text: name,
            loc: at,
        };
        let height = Token {
            text: height,
            loc: Loc::new(at.line, at.col + name.text.chars().count() as u32 + 1),
        };
        let name_ok = record(lex::name(name, "vertex name"), errors).is_some();
        match record(lex::integer(height, &format!("{what} height")), errors) {
            Some(value) if name_ok => points.push((name, Spanned::new(value, height.loc))),
            _ => ok = false,
        }
    }
    ok.then_some(WrittenSlope {
        loc: value.loc,
        points,
    })
}

/// The values of a `sector` line named `name`, if all are valid (each bad one is reported):
/// its heights, textures and light, and its mover's words (`flags`, from
/// [`lex::split_flags`]) and settings.
fn parse_sector_values(
    directive: Token<'_>,
    name: Option<&str>,
    flags: &[Token<'_>],
    keys: &mut KeyValues<'_>,
    (slopes, [ceiling_linked, floor_linked]): (&[Option<WrittenSlope<'_>>; 2], [bool; 2]),
    errors: &mut Vec<Located>,
) -> Option<SourceSector> {
    let mut missing = |key: &str, example: &str| {
        errors.push((
            directive.loc,
            format!("sector needs {key}=; add e.g. {key}={example}"),
        ));
    };
    let floor = keys.take("floor");
    let ceil = keys.take("ceil");
    let floor_tex = keys.take("floor_tex");
    let ceil_tex = keys.take("ceil_tex");
    let light = keys.take("light");
    // A sloped floor or ceiling takes its heights from its slope: `floor=` or `ceil=` would say
    // a second thing.
    let [floor_slope, ceil_slope] = slopes;
    let mut both_given = Vec::new();
    // A slope written but not parsed was reported already: no "needs floor=" on top.
    let slope_written = [keys.has("floor_slope"), keys.has("ceil_slope")];
    for ((key, given, slope), written) in
        [("floor", floor, floor_slope), ("ceil", ceil, ceil_slope)]
            .into_iter()
            .zip(slope_written)
    {
        match (given, slope) {
            (None, None) if !written => missing(key, if key == "floor" { "0" } else { "128" }),
            (Some(t), Some(_)) => both_given.push((
                t.loc,
                format!("{key}= and {key}_slope= both give this height; keep one (a slope gives its heights at the vertices it lists)"),
            )),
            _ => {}
        }
    }
    let slope_floor = |slope: &Option<WrittenSlope<'_>>| {
        slope.as_ref().map(|s| {
            let low = s.points.iter().map(|(_, h)| h.value).min().unwrap_or(0);
            Spanned::new(low, s.loc)
        })
    };
    // A floor or ceiling that is a portal to another layer is never drawn: its texture may be
    // left out (the other plane's then stands in, as the tables want one).
    if floor_tex.is_none() && !(floor_linked && ceil_tex.is_some_and(|t| t.text != "sky")) {
        missing("floor_tex", "stone");
    }
    if ceil_tex.is_none() && !(ceiling_linked && floor_tex.is_some()) {
        missing("ceil_tex", "sky");
    }
    if let Some(t) = ceil_tex.filter(|t| ceiling_linked && t.text == "sky") {
        errors.push((
            t.loc,
            "a ceiling that is a portal to the sector above (ceil_portal=) shows no sky; remove ceil_tex=sky or the portal".to_string(),
        ));
    }
    let layer = match keys.take("layer") {
        Some(t) => record(lex::integer_in(t, "layer", 0, LAYER_MAX), errors)
            .map(|v| Spanned::new(v, t.loc)),
        None => Some(Spanned::new(0, directive.loc)),
    };
    errors.append(&mut both_given);
    // A slope's heights stand in until the slope is resolved against the sector's outline
    // (`crate::slopes`), which sets the lowest floor and highest ceiling at its vertices.
    let floor = match floor {
        Some(t) if floor_slope.is_none() => {
            record(lex::integer(t, "floor height"), errors).map(|v| Spanned::new(v, t.loc))
        }
        _ => slope_floor(floor_slope),
    };
    let ceil = match ceil {
        Some(t) if ceil_slope.is_none() => {
            record(lex::integer(t, "ceiling height"), errors).map(|v| Spanned::new(v, t.loc))
        }
        _ => ceil_slope.as_ref().map(|s| {
            let high = s.points.iter().map(|(_, h)| h.value).max().unwrap_or(0);
            Spanned::new(high, s.loc)
        }),
    };
    let floor_tex = floor_tex.or(ceil_tex.filter(|_| floor_linked));
    let ceil_tex = ceil_tex.or(floor_tex.filter(|_| ceiling_linked));
    let floor_texture = match floor_tex {
        Some(t) if t.text == "sky" => {
            errors.push((
                t.loc,
                "the sky can only be a ceiling; give the floor a texture".to_string(),
            ));
            None
        }
        Some(t) => texture_name(t, errors),
        None => None,
    };
    let ceiling = match ceil_tex {
        Some(t) if t.text == "sky" => Some(CeilingSource::Sky),
        Some(t) => texture_name(t, errors).map(CeilingSource::Texture),
        None => None,
    };
    let light = match light {
        Some(t) => record(lex::integer_in(t, "light", 0, 255), errors).map(|v| v as u8),
        None => Some(DEFAULT_LIGHT),
    };
    // `tag=` serves the mover and a switched light alike: parsed once, here.
    let tag_token = keys.take("tag");
    let tag = tag_token.and_then(|t| record(lex::tag(t, "tag"), errors));
    // Whether `tag=` has a switched light to serve, asked of the word alone: a bad value after
    // `switched=` is its own error, and should not make `tag=` one too.
    let switched = keys.has("switched");
    let light_effect = lex::light_options(keys, (tag_token, tag.clone()), errors);
    let mover = lex::mover_options(flags, keys, (tag_token, tag), switched, errors);
    Some(SourceSector {
        label: format!("sector '{}'", name?),
        loc: directive.loc,
        floor: floor?,
        ceil: ceil?,
        floor_slope: None,
        ceil_slope: None,
        floor_texture: floor_texture?,
        ceiling: ceiling?,
        light: light?,
        mover: mover?,
        light_effect: light_effect?,
        layer: layer?,
        above: None,
        below: None,
        walls: Vec::new(),
    })
}

fn parse_wall<'t>(
    directive: Token<'t>,
    positional: &[Token<'t>],
    flags: &[Token<'t>],
    keys: &mut KeyValues<'t>,
    errors: &mut Vec<Located>,
) -> Option<WrittenWall<'t>> {
    let words = expect_words(directive, positional, ["START", "END"], errors);
    let texture = keys.take("tex").and_then(|t| texture_name(t, errors));
    let portal = keys.take("portal");
    let upper = keys.take("upper").and_then(|t| texture_name(t, errors));
    let lower = keys.take("lower").and_then(|t| texture_name(t, errors));
    let middle = keys.take("mid").and_then(|t| {
        record(lex::name(t, "sprite name"), errors).map(|name| Spanned::new(name, t.loc))
    });
    let switch = keys.take("switch").and_then(|t| texture_name(t, errors));
    let tag = keys
        .take("tag")
        .and_then(|t| record(lex::tag(t, "tag"), errors));
    let trigger = keys
        .take("trigger")
        .and_then(|t| record(lex::tag(t, "trigger"), errors));
    let flag = |word: &str| flags.iter().find(|f| f.text == word).map(|f| f.loc);
    let mut offset = |key: &str| match keys.take(key) {
        Some(t) => {
            record(lex::integer(t, "texture offset"), errors).map(|v| Spanned::new(v, t.loc))
        }
        None => Some(Spanned::new(0, directive.loc)),
    };
    let x_offset = offset("xoff");
    let y_offset = offset("yoff");
    let [start, end] = words?;
    Some(WrittenWall {
        loc: directive.loc,
        start,
        end,
        texture,
        portal,
        upper,
        lower,
        x_offset: x_offset?,
        y_offset: y_offset?,
        middle,
        blocks: flag("blocks"),
        translucent: flag("translucent"),
        switch,
        tag,
        trigger,
    })
}

fn parse_place(
    directive: Token<'_>,
    x: Token<'_>,
    y: Token<'_>,
    keys: &mut KeyValues<'_>,
    errors: &mut Vec<Located>,
) -> Option<SourcePlace> {
    let angle = match keys.take("angle") {
        Some(t) => record(lex::angle_degrees(t), errors),
        None => Some(0),
    };
    let layer = match keys.take("layer") {
        Some(t) => record(lex::integer_in(t, "layer", 0, LAYER_MAX), errors)
            .map(|v| Some(Spanned::new(v, t.loc))),
        None => Some(None),
    };
    let x_fx8 = record(lex::position_fx8(x, "x"), errors);
    let y_fx8 = record(lex::position_fx8(y, "y"), errors);
    Some(SourcePlace {
        loc: directive.loc,
        x_fx8: Spanned::new(x_fx8?, x.loc),
        y_fx8: Spanned::new(y_fx8?, y.loc),
        angle: angle?,
        layer: layer?,
    })
}

/// The `player` line's body: `eye=` (standing eye height), `height=` (the body's; default the
/// eye plus the native headroom) and `step=`, each defaulting to [`PlayerSize::NATIVE`].
pub(crate) fn parse_player_size(
    keys: &mut KeyValues<'_>,
    errors: &mut Vec<Located>,
) -> Option<PlayerSize> {
    let native = PlayerSize::NATIVE;
    let eye_token = keys.take("eye");
    let eye = match eye_token {
        Some(t) => record(
            lex::integer_in(
                t,
                "eye height",
                i64::from(PlayerSize::EYE_HEIGHT_MIN),
                i64::from(PlayerSize::EYE_HEIGHT_MAX),
            ),
            errors,
        ),
        None => Some(i64::from(native.eye_height)),
    };
    let step = match keys.take("step") {
        Some(t) => record(
            lex::integer_in(t, "step", 0, i64::from(PlayerSize::STEP_UP_MAX)),
            errors,
        ),
        None => Some(i64::from(native.step_up)),
    };
    let eye = i32::try_from(eye?).ok()?;
    let height = match keys.take("height") {
        Some(t) => record(
            lex::integer_in(
                t,
                "body height",
                i64::from(eye) + 1,
                i64::from(eye) + i64::from(PlayerSize::EYE_HEIGHT_MAX),
            )
            .map_err(|(loc, message)| {
                (
                    loc,
                    format!("{message} (the eye, at {eye}, keeps at least 1 below the ceiling)"),
                )
            }),
            errors,
        ),
        None => Some(i64::from(eye + native.headroom())),
    };
    Some(PlayerSize {
        eye_height: eye,
        height: i32::try_from(height?).ok()?,
        step_up: i32::try_from(step?).ok()?,
    })
}

/// Turns vertex and sector names into indices.
fn resolve_walls(
    sectors: Vec<WrittenSector<'_>>,
    vertex_names: &HashMap<String, usize>,
    sector_names: &HashMap<String, usize>,
    errors: &mut Vec<Located>,
) -> Vec<SourceSector> {
    let mut resolved = Vec::with_capacity(sectors.len());
    let vertex = |token: Token<'_>, errors: &mut Vec<Located>| {
        let found = vertex_names.get(token.text).copied();
        if found.is_none() {
            errors.push((
                token.loc,
                format!(
                    "unknown vertex '{}'; declare it with `vertex {} X Y`",
                    token.text, token.text
                ),
            ));
        }
        found
    };
    for WrittenSector {
        mut sector,
        walls,
        slopes,
        links,
    } in sectors
    {
        let [above, below] = links.map(|token| {
            let token = token?;
            match sector_names.get(token.text) {
                Some(&index) => Some(Spanned::new(index, token.loc)),
                None => {
                    errors.push((
                        token.loc,
                        format!("unknown sector '{}'; a floor or ceiling portal must name a sector declared in this file", token.text),
                    ));
                    None
                }
            }
        });
        sector.above = above;
        sector.below = below;
        let [floor_slope, ceil_slope] = slopes.map(|slope| {
            let slope = slope?;
            let points: Vec<_> = slope
                .points
                .into_iter()
                .filter_map(|(name, height)| {
                    Some((Spanned::new(vertex(name, errors)?, name.loc), height))
                })
                .collect();
            Some(SourceSlope {
                loc: slope.loc,
                points,
            })
        });
        sector.floor_slope = floor_slope;
        sector.ceil_slope = ceil_slope;
        for wall in walls {
            let start = vertex(wall.start, errors);
            let end = vertex(wall.end, errors);
            let portal = match wall.portal {
                Some(token) => match sector_names.get(token.text) {
                    Some(&index) => Some(Spanned::new(index, token.loc)),
                    None => {
                        errors.push((
                            token.loc,
                            format!("unknown sector '{}'; portal= must name a sector declared in this file", token.text),
                        ));
                        continue;
                    }
                },
                None => None,
            };
            let (Some(start), Some(end)) = (start, end) else {
                continue;
            };
            sector.walls.push(SourceWall {
                loc: wall.loc,
                start,
                end,
                texture: wall.texture,
                portal,
                upper: wall.upper,
                lower: wall.lower,
                x_offset: wall.x_offset,
                y_offset: wall.y_offset,
                middle: wall.middle,
                blocks: wall.blocks,
                translucent: wall.translucent,
                switch: wall.switch,
                tag: wall.tag,
                trigger: wall.trigger,
            });
        }
        resolved.push(sector);
    }
    resolved
}
