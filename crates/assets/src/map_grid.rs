//! The `.grid` format (specified in `docs/MAP_FORMAT.md`): a legend of cell characters, then an
//! ASCII picture of the map, one character per cell, rows going down (+y) and columns going
//! right (+x).
//!
//! Open cells of the same kind are merged into axis-aligned rectangles (greedy: widest run
//! first, then as many rows down as fit), each one sector. Every side of a rectangle is split
//! wherever what lies across it changes, so two neighbouring rectangles always see their shared
//! stretch as the same segment (`a → b` on one side, `b → a` on the other), even where they
//! only partly overlap; the split points become collinear vertices of the outline.

use std::collections::{BTreeSet, HashMap};

use portalcast_format::limits::WORLD_COORD_MAX;
use portalcast_format::PlayerSize;

use crate::diag::{Loc, Located};
use crate::geometry::Point;
use crate::lex::{self, KeyValues, Token};
use crate::source::{
    CeilingSource, MoverKind, SourceMap, SourceMover, SourcePlace, SourceSector, SourceThing,
    SourceVertex, SourceWall, Spanned, ThingOptions,
};

/// Cell side in world units when the file has no `cell` line.
const DEFAULT_CELL: i64 = 64;
/// Largest grid side in cells; keeps compile time and vertex counts small.
const GRID_SIDE_MAX: usize = 256;

const OPEN_KEYS: &[&str] = &["floor", "ceil", "floor_tex", "ceil_tex", "light", "side"];
const SOLID_KEYS: &[&str] = &["tex"];
const PLAYER_KEYS: &[&str] = &["on", "angle", "eye", "height", "step"];
const THING_KEYS: &[&str] = &["on", "angle", "z", "radius", "anim"];
const DOOR_KEYS: &[&str] = &["on", "tex", "speed", "wait"];
/// The bare words a `door` legend line may carry.
const DOOR_FLAGS: &[&str] = &["touch"];

struct OpenKind {
    symbol: char,
    loc: Loc,
    floor: Spanned<i64>,
    ceil: Spanned<i64>,
    floor_texture: Spanned<String>,
    ceiling: CeilingSource,
    light: u8,
    side: Option<Spanned<String>>,
    /// A door kind's mover (`door` legend lines); `None` for `open` kinds.
    mover: Option<SourceMover>,
}

/// A `door` legend line: cells of `symbol` are doors with the heights and textures of the open
/// kind `on`, whose face (the upper strip of the walls into them) shows `face`.
struct DoorLine<'t> {
    symbol: char,
    on: Token<'t>,
    face: Spanned<String>,
    mover: SourceMover,
}

/// Something standing on an open cell: the player (`sprite: None`) or a thing.
struct Marker<'t> {
    symbol: char,
    loc: Loc,
    sprite: Option<Spanned<String>>,
    on: Token<'t>,
    angle: u16,
    options: ThingOptions,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Cell {
    /// Index into the solid kinds.
    Solid(usize),
    /// Index into the open kinds.
    Open(usize),
}

/// What lies across one unit of a rectangle's side.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Across {
    Solid(usize),
    Area(usize),
}

/// One wall of a rectangle's outline: from, to, and what lies across.
type Segment = (Point, Point, Across);

struct Rectangle {
    kind: usize,
    column: usize,
    row: usize,
    width: usize,
    height: usize,
}

fn record<T>(result: Result<T, Located>, errors: &mut Vec<Located>) -> Option<T> {
    result.map_err(|e| errors.push(e)).ok()
}

fn symbol_of(token: Token<'_>, errors: &mut Vec<Located>) -> Option<char> {
    let mut chars = token.text.chars();
    match (chars.next(), chars.next()) {
        (Some(c), None) => Some(c),
        _ => {
            errors.push((
                token.loc,
                format!(
                    "'{}' is not a single cell character; the legend maps one character at a time",
                    token.text
                ),
            ));
            None
        }
    }
}

/// Parses a `.grid` file into sectors and portals.
pub(crate) fn parse(text: &str) -> Result<SourceMap, Vec<Located>> {
    let mut errors = Vec::new();
    let mut cell = DEFAULT_CELL;
    let mut solids: Vec<(char, Spanned<String>)> = Vec::new();
    let mut opens: Vec<OpenKind> = Vec::new();
    let mut markers: Vec<Marker<'_>> = Vec::new();
    let mut player_size = PlayerSize::NATIVE;
    let mut doors: Vec<DoorLine<'_>> = Vec::new();
    let mut grid_start: Option<usize> = None;
    let mut symbols: HashMap<char, Loc> = HashMap::new();
    let mut player_seen = false;

    let lines: Vec<&str> = text.lines().collect();
    for (index, line) in lines.iter().enumerate() {
        let line_no = u32::try_from(index + 1).unwrap_or(u32::MAX);
        let mut words = lex::tokens(line, line_no);
        let Some(&directive) = words.first() else {
            continue;
        };
        if directive.text.starts_with('#') {
            continue;
        }
        if directive.text == "grid" {
            if words.len() > 1 {
                errors.push((
                    words[1].loc,
                    "nothing may follow `grid` on its line; the rows start on the next line"
                        .to_string(),
                ));
            }
            grid_start = Some(index + 1);
            break;
        }
        // The second word of a legend line is a cell character, which may well be '#'.
        let symbol_slot = matches!(
            directive.text,
            "solid" | "open" | "door" | "player" | "thing"
        );
        let first_comment_word = if symbol_slot { 2 } else { 1 };
        if let Some(cut) = words
            .iter()
            .skip(first_comment_word)
            .position(|w| w.text.starts_with('#'))
        {
            words.truncate(cut + first_comment_word);
        }
        let symbol = if symbol_slot {
            match words.get(1) {
                Some(&token) => {
                    let symbol = symbol_of(token, &mut errors);
                    if let Some(symbol) = symbol {
                        if let Some(first) = symbols.insert(symbol, token.loc) {
                            errors.push((
                                token.loc,
                                format!("cell character '{symbol}' is already defined on line {}; use another character", first.line),
                            ));
                        }
                    }
                    symbol
                }
                None => {
                    errors.push((
                        directive.loc,
                        format!("{} needs a cell character after it", directive.text),
                    ));
                    continue;
                }
            }
        } else {
            None
        };
        let rest = if symbol_slot {
            &words[2..]
        } else {
            &words[1..]
        };
        let (rest, flags) = match directive.text {
            "thing" => {
                lex::split_flags(rest, 1, lex::THING_FLAGS, "thing", THING_KEYS, &mut errors)
            }
            "door" => lex::split_flags(rest, 0, DOOR_FLAGS, "door", DOOR_KEYS, &mut errors),
            _ => (rest.to_vec(), Vec::new()),
        };
        let (positional, mut keys) = KeyValues::split(&rest, &mut errors);
        match directive.text {
            "cell" => {
                keys.report_unknown("cell", &[], &mut errors);
                match positional.as_slice() {
                    [size] => {
                        if let Some(size) = record(lex::integer_in(*size, "cell size", 1, i64::from(WORLD_COORD_MAX)), &mut errors) {
                            cell = size;
                        }
                    }
                    _ => errors.push((directive.loc, "cell takes one value, the cell side in world units (e.g. `cell 64`)".to_string())),
                }
            }
            "solid" => {
                let texture = keys.take("tex");
                keys.report_unknown("solid", SOLID_KEYS, &mut errors);
                extra_words(&positional, &mut errors);
                match (symbol, texture) {
                    (Some(symbol), Some(texture)) => {
                        if let Some(name) = record(lex::name(texture, "texture name"), &mut errors) {
                            solids.push((symbol, Spanned::new(name, texture.loc)));
                        }
                    }
                    (_, None) => errors.push((directive.loc, "solid needs tex=TEXTURE (e.g. `solid # tex=brick`)".to_string())),
                    _ => {}
                }
            }
            "open" => {
                extra_words(&positional, &mut errors);
                let kind = parse_open(directive, &mut keys, &mut errors);
                keys.report_unknown("open", OPEN_KEYS, &mut errors);
                if let (Some(symbol), Some(mut kind)) = (symbol, kind) {
                    kind.symbol = symbol;
                    opens.push(kind);
                }
            }
            "door" => {
                let door = parse_door(directive, &flags, &mut keys, &mut errors);
                keys.report_unknown("door", DOOR_KEYS, &mut errors);
                if let (Some(symbol), Some(mut door)) = (symbol, door) {
                    door.symbol = symbol;
                    doors.push(door);
                }
            }
            "player" | "thing" => {
                let sprite = if directive.text == "thing" {
                    match positional.as_slice() {
                        [sprite] => record(lex::name(*sprite, "sprite name"), &mut errors).map(|n| Some(Spanned::new(n, sprite.loc))),
                        _ => {
                            errors.push((directive.loc, "thing takes a cell character and a sprite name (e.g. `thing t torch on=.`)".to_string()));
                            None
                        }
                    }
                } else {
                    extra_words(&positional, &mut errors);
                    Some(None)
                };
                let on = keys.take("on");
                let angle = match keys.take("angle") {
                    Some(t) => record(lex::angle_degrees(t), &mut errors),
                    None => Some(0),
                };
                let (options, accepted) = if directive.text == "thing" {
                    (lex::thing_options(&flags, &mut keys, &mut errors), THING_KEYS)
                } else {
                    if let Some(size) = crate::map_text::parse_player_size(&mut keys, &mut errors) {
                        if !player_seen {
                            player_size = size;
                        }
                    }
                    (Some(ThingOptions::default()), PLAYER_KEYS)
                };
                keys.report_unknown(directive.text, accepted, &mut errors);
                player_seen |= directive.text == "player";
                if on.is_none() {
                    errors.push((directive.loc, format!("{} needs on=C, the open cell character it stands on", directive.text)));
                }
                if let (Some(symbol), Some(sprite), Some(on), Some(angle), Some(options)) = (symbol, sprite, on, angle, options) {
                    markers.push(Marker { symbol, loc: directive.loc, sprite, on, angle, options });
                }
            }
            other => errors.push((
                directive.loc,
                format!("unknown directive '{other}'; expected cell, solid, open, door, player, thing or grid"),
            )),
        }
    }

    let Some(grid_start) = grid_start else {
        errors.push((
            Loc::START,
            "no `grid` line; end the legend with `grid` and draw the map below it".to_string(),
        ));
        return Err(errors);
    };
    // Each door is a kind of its own: the heights and textures of its open kind, its face as the
    // `side` the walls into it show, and its mover.
    for door in doors {
        let on = door
            .on
            .text
            .chars()
            .next()
            .filter(|_| door.on.text.chars().count() == 1);
        let Some(base) = on.and_then(|k| opens.iter().find(|o| o.symbol == k && o.mover.is_none()))
        else {
            errors.push((
                door.on.loc,
                format!(
                    "on={} is not an open cell character; name one defined by an `open` line (the door takes its floor, ceiling and textures)",
                    door.on.text
                ),
            ));
            continue;
        };
        let kind = OpenKind {
            symbol: door.symbol,
            loc: door.mover.loc,
            floor: base.floor.clone(),
            ceil: base.ceil.clone(),
            floor_texture: base.floor_texture.clone(),
            ceiling: base.ceiling.clone(),
            light: base.light,
            side: Some(door.face),
            mover: Some(door.mover),
        };
        opens.push(kind);
    }
    let mut marker_kinds = Vec::new();
    for marker in &markers {
        let kind = marker
            .on
            .text
            .chars()
            .next()
            .filter(|_| marker.on.text.chars().count() == 1);
        match kind.and_then(|k| opens.iter().position(|o| o.symbol == k)) {
            Some(kind) => marker_kinds.push(kind),
            None => errors.push((
                marker.on.loc,
                format!(
                    "on={} is not an open cell character; name one defined by an `open` line",
                    marker.on.text
                ),
            )),
        }
    }
    if !player_seen {
        errors.push((
            Loc::START,
            "no player; add `player @ on=. angle=0` and put '@' in the grid".to_string(),
        ));
    }
    if !errors.is_empty() {
        return Err(errors);
    }

    let grid = read_cells(
        &lines,
        grid_start,
        &solids,
        &opens,
        &markers,
        &marker_kinds,
        &mut errors,
    );
    if !errors.is_empty() {
        return Err(errors);
    }
    let Some((cells, placed)) = grid else {
        return Err(errors);
    };
    let width = cells[0].len();
    let height = cells.len();
    if (width.max(height) as i64) * cell > i64::from(WORLD_COORD_MAX) {
        errors.push((
            Loc::new(line_of(grid_start), 1),
            format!(
                "the grid is {width}x{height} cells of {cell} units, beyond the map limit of {WORLD_COORD_MAX} units; use fewer or smaller cells"
            ),
        ));
        return Err(errors);
    }

    let (rectangles, owner) = merge_rectangles(&cells);
    let builder = OutlineBuilder {
        cells: &cells,
        owner: &owner,
        cell,
    };
    let mut vertices = Vec::new();
    let mut vertex_at = HashMap::new();
    let mut sectors = Vec::new();
    let mut missing_sides = BTreeSet::new();
    for rectangle in &rectangles {
        let kind = &opens[rectangle.kind];
        let loc = Loc::new(
            line_of(grid_start + rectangle.row),
            rectangle.column as u32 + 1,
        );
        let mut walls = Vec::new();
        for (from, to, across) in builder.outline(rectangle) {
            let mut vertex = |p: (i64, i64)| {
                *vertex_at.entry(p).or_insert_with(|| {
                    vertices.push(SourceVertex {
                        label: format!("corner ({}, {})", p.0, p.1),
                        x: Spanned::new(p.0, loc),
                        y: Spanned::new(p.1, loc),
                    });
                    vertices.len() - 1
                })
            };
            let (start, end) = (vertex(from), vertex(to));
            let mut wall = SourceWall::new(loc, start, end);
            match across {
                Across::Solid(solid) => wall.texture = Some(solids[solid].1.clone()),
                Across::Area(other) => {
                    let there = &opens[rectangles[other].kind];
                    let both_sky = matches!(kind.ceiling, CeilingSource::Sky)
                        && matches!(there.ceiling, CeilingSource::Sky);
                    // A door's ceiling comes down to its floor: the walls into it show its face.
                    let lowest_ceiling = |kind: &OpenKind| match kind.mover {
                        Some(_) => kind.floor.value,
                        None => kind.ceil.value,
                    };
                    let upper_shows = lowest_ceiling(there) < kind.ceil.value && !both_sky;
                    let lower_shows = there.floor.value > kind.floor.value;
                    if (upper_shows || lower_shows) && there.side.is_none() {
                        missing_sides.insert((rectangles[other].kind, rectangle.kind));
                    }
                    if upper_shows {
                        wall.upper = there.side.clone();
                    }
                    if lower_shows {
                        wall.lower = there.side.clone();
                    }
                    wall.portal = Some(Spanned::new(other, loc));
                }
            }
            walls.push(wall);
        }
        sectors.push(SourceSector {
            label: format!(
                "area '{}' at row {}, column {}",
                kind.symbol,
                rectangle.row + 1,
                rectangle.column + 1
            ),
            loc,
            floor: kind.floor.clone(),
            ceil: kind.ceil.clone(),
            floor_slope: None,
            ceil_slope: None,
            floor_texture: kind.floor_texture.clone(),
            ceiling: kind.ceiling.clone(),
            light: kind.light,
            mover: kind.mover.clone(),
            light_effect: None,
            layer: Spanned::new(0, loc),
            above: None,
            below: None,
            walls,
        });
    }
    for (higher, lower) in missing_sides {
        errors.push((
            opens[higher].loc,
            format!(
                "open '{}' needs side=TEXTURE: next to '{}' its floor is higher or its ceiling lower, and that step shows",
                opens[higher].symbol, opens[lower].symbol
            ),
        ));
    }
    if !errors.is_empty() {
        return Err(errors);
    }

    let place = |marker: &Marker<'_>, (row, column): (usize, usize)| {
        let loc = Loc::new(line_of(grid_start + row), column as u32 + 1);
        // Cell centres are never on a cell edge, so never on a wall.
        let centre = |index: usize| (index as i64 * cell * 2 + cell) * 128;
        SourcePlace {
            loc,
            x_fx8: Spanned::new(centre(column), loc),
            y_fx8: Spanned::new(centre(row), loc),
            angle: marker.angle,
            layer: None,
        }
    };
    let mut player = None;
    let mut things = Vec::new();
    for (marker_index, at) in placed {
        let marker = &markers[marker_index];
        let here = place(marker, at);
        match &marker.sprite {
            Some(sprite) => things.push(SourceThing {
                sprite: sprite.clone(),
                place: here,
                options: marker.options.clone(),
            }),
            None if player.is_some() => errors.push((
                here.loc,
                format!("second player '{}' in the grid; keep one", marker.symbol),
            )),
            None => player = Some(here),
        }
    }
    match player {
        Some(player) if errors.is_empty() => Ok(SourceMap {
            vertices,
            sectors,
            player,
            player_size,
            things,
        }),
        Some(_) => Err(errors),
        None => {
            let marker = markers
                .iter()
                .find(|m| m.sprite.is_none())
                .map_or(Loc::START, |m| m.loc);
            errors.push((
                marker,
                "the player character does not appear in the grid; put it on the start cell"
                    .to_string(),
            ));
            Err(errors)
        }
    }
}

fn line_of(index: usize) -> u32 {
    u32::try_from(index + 1).unwrap_or(u32::MAX)
}

fn extra_words(words: &[Token<'_>], errors: &mut Vec<Located>) {
    if let Some(word) = words.first() {
        errors.push((
            word.loc,
            format!("unexpected '{}'; settings are written key=value", word.text),
        ));
    }
}

fn parse_open(
    directive: Token<'_>,
    keys: &mut KeyValues<'_>,
    errors: &mut Vec<Located>,
) -> Option<OpenKind> {
    let mut required = |key: &str, example: &str| {
        let token = keys.take(key);
        if token.is_none() {
            errors.push((
                directive.loc,
                format!("open needs {key}=; add e.g. {key}={example}"),
            ));
        }
        token
    };
    let floor = required("floor", "0");
    let ceil = required("ceil", "128");
    let floor_tex = required("floor_tex", "stone");
    let ceil_tex = required("ceil_tex", "sky");
    let height = |token: Option<Token<'_>>, what: &str, errors: &mut Vec<Located>| {
        token.and_then(|t| record(lex::integer(t, what), errors).map(|v| Spanned::new(v, t.loc)))
    };
    let floor = height(floor, "floor height", errors);
    let ceil = height(ceil, "ceiling height", errors);
    let texture = |token: Token<'_>, errors: &mut Vec<Located>| {
        record(lex::name(token, "texture name"), errors).map(|n| Spanned::new(n, token.loc))
    };
    let floor_texture = match floor_tex {
        Some(t) if t.text == "sky" => {
            errors.push((
                t.loc,
                "the sky can only be a ceiling; give the floor a texture".to_string(),
            ));
            None
        }
        Some(t) => texture(t, errors),
        None => None,
    };
    let ceiling = match ceil_tex {
        Some(t) if t.text == "sky" => Some(CeilingSource::Sky),
        Some(t) => texture(t, errors).map(CeilingSource::Texture),
        None => None,
    };
    let light = match keys.take("light") {
        Some(t) => record(lex::integer_in(t, "light", 0, 255), errors).map(|v| v as u8),
        None => Some(portalcast_format::LIGHT_NEUTRAL),
    };
    let side = match keys.take("side") {
        Some(t) => Some(texture(t, errors)?),
        None => None,
    };
    Some(OpenKind {
        symbol: ' ',
        loc: directive.loc,
        floor: floor?,
        ceil: ceil?,
        floor_texture: floor_texture?,
        ceiling: ceiling?,
        light: light?,
        side,
        mover: None,
    })
}

/// Parses a `door` legend line's settings: `on=K` (the open kind whose heights and textures the
/// door has), `tex=TEX` (its face), the word `touch`, `speed=` and `wait=`.
fn parse_door<'t>(
    directive: Token<'t>,
    flags: &[Token<'t>],
    keys: &mut KeyValues<'t>,
    errors: &mut Vec<Located>,
) -> Option<DoorLine<'t>> {
    let on = keys.take("on");
    let face = keys.take("tex");
    if on.is_none() {
        errors.push((
            directive.loc,
            "door needs on=K, the open cell character whose floor, ceiling and textures it has (e.g. `door D on=. tex=metal`)".to_string(),
        ));
    }
    if face.is_none() {
        errors.push((
            directive.loc,
            "door needs tex=TEXTURE, its face: the wall above the doorway while it is closed (e.g. `door D on=. tex=metal`)".to_string(),
        ));
    }
    let face = face.and_then(|t| {
        record(lex::name(t, "texture name"), errors).map(|name| Spanned::new(name, t.loc))
    });
    let (default_speed, default_wait) = MoverKind::Door.defaults();
    let mut number = |key: &str, min: i64, max: i64, default: u16| match keys.take(key) {
        Some(t) => record(lex::integer_in(t, key, min, max), errors).map(|v| v as u16),
        None => Some(default),
    };
    let speed = number("speed", 1, lex::MOVER_SPEED_MAX, default_speed);
    let wait = number("wait", 0, i64::from(u16::MAX), default_wait);
    Some(DoorLine {
        symbol: ' ',
        on: on?,
        face: face?,
        mover: SourceMover {
            kind: MoverKind::Door,
            loc: directive.loc,
            height: None,
            touch: flags.iter().any(|f| f.text == "touch"),
            locked: None,
            speed: speed?,
            wait: wait?,
            tag: None,
        },
    })
}

type Placed = Vec<(usize, (usize, usize))>;

/// Reads the rows after `grid`: the cell kinds, and where each marker stands.
fn read_cells(
    lines: &[&str],
    grid_start: usize,
    solids: &[(char, Spanned<String>)],
    opens: &[OpenKind],
    markers: &[Marker<'_>],
    marker_kinds: &[usize],
    errors: &mut Vec<Located>,
) -> Option<(Vec<Vec<Cell>>, Placed)> {
    let mut rows: Vec<&str> = lines
        .get(grid_start..)
        .unwrap_or(&[])
        .iter()
        .map(|l| l.trim_end())
        .collect();
    while rows.last().is_some_and(|r| r.is_empty()) {
        rows.pop();
    }
    if rows.len() < 3 {
        errors.push((
            Loc::new(line_of(grid_start), 1),
            "the grid needs at least 3 rows (a border of solid cells around open ones)".to_string(),
        ));
        return None;
    }
    let width = rows[0].chars().count();
    if rows.len() > GRID_SIDE_MAX || width > GRID_SIDE_MAX {
        errors.push((
            Loc::new(line_of(grid_start), 1),
            format!(
                "the grid is larger than {GRID_SIDE_MAX}x{GRID_SIDE_MAX} cells; make it smaller"
            ),
        ));
        return None;
    }
    let mut cells = Vec::with_capacity(rows.len());
    let mut placed = Vec::new();
    for (row_index, row) in rows.iter().enumerate() {
        let line = line_of(grid_start + row_index);
        let count = row.chars().count();
        if count != width {
            errors.push((
                Loc::new(line, 1),
                format!("row has {count} cells but the first row has {width}; make every row the same width"),
            ));
            continue;
        }
        let mut cells_row = Vec::with_capacity(width);
        for (column, symbol) in row.chars().enumerate() {
            let loc = Loc::new(line, column as u32 + 1);
            let cell = if let Some(solid) = solids.iter().position(|(c, _)| *c == symbol) {
                Cell::Solid(solid)
            } else if let Some(open) = opens.iter().position(|o| o.symbol == symbol) {
                Cell::Open(open)
            } else if let Some(marker) = markers.iter().position(|m| m.symbol == symbol) {
                placed.push((marker, (row_index, column)));
                Cell::Open(marker_kinds[marker])
            } else {
                errors.push((
                    loc,
                    format!(
                        "cell character '{symbol}' is not in the legend; define it above `grid`"
                    ),
                ));
                Cell::Solid(0)
            };
            let border =
                row_index == 0 || row_index + 1 == rows.len() || column == 0 || column + 1 == width;
            if border && matches!(cell, Cell::Open(_)) {
                errors.push((
                    loc,
                    "open cell on the grid's border; surround the map with solid cells".to_string(),
                ));
            }
            cells_row.push(cell);
        }
        cells.push(cells_row);
    }
    if width < 3 {
        errors.push((
            Loc::new(line_of(grid_start), 1),
            "the grid needs at least 3 columns (a border of solid cells around open ones)"
                .to_string(),
        ));
    }
    if errors.is_empty() {
        Some((cells, placed))
    } else {
        None
    }
}

/// Greedy maximal rectangles of equal open cells, scanning rows top to bottom. Returns the
/// rectangles and, per cell, the rectangle that owns it.
fn merge_rectangles(cells: &[Vec<Cell>]) -> (Vec<Rectangle>, Vec<Vec<Option<usize>>>) {
    let (height, width) = (cells.len(), cells[0].len());
    let mut owner = vec![vec![None; width]; height];
    let mut rectangles = Vec::new();
    for row in 0..height {
        for column in 0..width {
            let Cell::Open(kind) = cells[row][column] else {
                continue;
            };
            if owner[row][column].is_some() {
                continue;
            }
            let free = |r: usize, c: usize, owner: &Vec<Vec<Option<usize>>>| {
                cells[r][c] == Cell::Open(kind) && owner[r][c].is_none()
            };
            let mut span = 1;
            while column + span < width && free(row, column + span, &owner) {
                span += 1;
            }
            let mut rows = 1;
            while row + rows < height
                && (column..column + span).all(|c| free(row + rows, c, &owner))
            {
                rows += 1;
            }
            let id = rectangles.len();
            for owned_row in owner.iter_mut().skip(row).take(rows) {
                for slot in owned_row.iter_mut().skip(column).take(span) {
                    *slot = Some(id);
                }
            }
            rectangles.push(Rectangle {
                kind,
                column,
                row,
                width: span,
                height: rows,
            });
        }
    }
    (rectangles, owner)
}

struct OutlineBuilder<'g> {
    cells: &'g [Vec<Cell>],
    owner: &'g [Vec<Option<usize>>],
    cell: i64,
}

impl OutlineBuilder<'_> {
    fn across(&self, row: usize, column: usize) -> Across {
        match (self.cells[row][column], self.owner[row][column]) {
            (_, Some(rectangle)) => Across::Area(rectangle),
            (Cell::Solid(solid), None) => Across::Solid(solid),
            // Every open cell belongs to a rectangle.
            (Cell::Open(_), None) => Across::Solid(0),
        }
    }

    /// The rectangle's walls, clockwise (y down): top left to right, right side downward,
    /// bottom right to left, left side upward. Each side is cut where what lies across changes.
    fn outline(&self, r: &Rectangle) -> Vec<Segment> {
        let c = self.cell;
        let (left, top) = (r.column, r.row);
        let (right, bottom) = (r.column + r.width, r.row + r.height);
        let at = |column: usize, row: usize| (column as i64 * c, row as i64 * c);
        // Each unit step of the walk: its start corner, its end corner, and the cell across.
        let mut steps = Vec::new();
        for column in left..right {
            steps.push((
                at(column, top),
                at(column + 1, top),
                self.across(top - 1, column),
            ));
        }
        for row in top..bottom {
            steps.push((at(right, row), at(right, row + 1), self.across(row, right)));
        }
        for column in (left..right).rev() {
            steps.push((
                at(column + 1, bottom),
                at(column, bottom),
                self.across(bottom, column),
            ));
        }
        for row in (top..bottom).rev() {
            steps.push((at(left, row + 1), at(left, row), self.across(row, left - 1)));
        }
        let corner_steps = [r.width, r.width + r.height, 2 * r.width + r.height];
        let mut walls: Vec<Segment> = Vec::new();
        for (index, (from, to, across)) in steps.into_iter().enumerate() {
            match walls.last_mut() {
                Some(last) if last.2 == across && !corner_steps.contains(&index) => last.1 = to,
                _ => walls.push((from, to, across)),
            }
        }
        walls
    }
}
