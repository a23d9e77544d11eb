//! The Start menu: a list of settings drawn over the view with a 3×5 pixel font.
//!
//! Each entry is a label and a value that Left/Right (or A) change; Up/Down pick the entry,
//! Start or B close the menu. The game pauses while it is open. To add a setting, add an
//! [`Entry`] variant to [`ENTRIES`] and say in `game.rs` how it shows and changes.
//!
//! The menu is drawn into the back page through the same [`Canvas`] the renderer uses, as
//! horizontal runs of one colour, after the 3D view: so the host draws exactly what the ROM
//! draws, and the emulator test compares menu frames pixel for pixel too. Its size on the
//! screen is the same at every resolution: a font pixel is 2×2 screen pixels.

use crate::demo::lighting_label;
use portalcast::frame::Resolution;
use portalcast::raster::flat::{FlatTexture, PackedUv};
use portalcast::raster::Canvas;
use portalcast::render::light::Lighting;
use portalcast::render::view::{Floors, Preprocessing, TexturePlacement, ThingsShown};
use portalcast::text::{glyph_lit, GLYPH_HEIGHT, GLYPH_WIDTH};

/// One line of the menu.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Entry {
    /// Render resolution.
    Resolution,
    /// Lighting rule.
    Lighting,
    /// Which shipped map is played (changing it starts the map afresh).
    Map,
    /// Fly mode.
    Fly,
    /// Run rather than walk.
    Run,
    /// Where texels are read from (EWRAM or the cartridge).
    Textures,
    /// The thesis' scene preprocessing (merged sector visits), on or off.
    Preprocessing,
    /// Floors and ceilings at full or half horizontal resolution (240 wide only).
    Floors,
    /// The heads-up display: frame rate and cycles of the last frame.
    Hud,
    /// Things drawn or not.
    Things,
}

/// The menu's entries, top to bottom.
pub const ENTRIES: [Entry; 10] = [
    Entry::Resolution,
    Entry::Lighting,
    Entry::Map,
    Entry::Fly,
    Entry::Run,
    Entry::Textures,
    Entry::Preprocessing,
    Entry::Floors,
    Entry::Hud,
    Entry::Things,
];

impl Entry {
    /// The label shown left of the value.
    pub const fn label(self) -> &'static str {
        match self {
            Entry::Resolution => "RES",
            Entry::Lighting => "LIGHT",
            Entry::Map => "MAP",
            Entry::Fly => "FLY",
            Entry::Run => "RUN",
            Entry::Textures => "TEX",
            Entry::Preprocessing => "PREP",
            Entry::Floors => "FLOOR",
            Entry::Hud => "HUD",
            Entry::Things => "THING",
        }
    }
}

/// The values the menu shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shown<'a> {
    /// Render resolution.
    pub resolution: Resolution,
    /// Lighting rule.
    pub lighting: Lighting,
    /// The map's name.
    pub map: &'a str,
    /// Fly mode.
    pub fly: bool,
    /// Running.
    pub run: bool,
    /// The heads-up display (frame rate and cycles).
    pub hud: bool,
    /// Texture placement.
    pub textures: TexturePlacement,
    /// Scene preprocessing.
    pub preprocessing: Preprocessing,
    /// Floor resolution.
    pub floors: Floors,
    /// Things drawn or not.
    pub things: ThingsShown,
}

impl Entry {
    /// The value shown for this entry.
    pub fn value<'a>(self, shown: &Shown<'a>) -> &'a str {
        let on_off = |on: bool| if on { "on" } else { "off" };
        match self {
            Entry::Resolution => shown.resolution.label(),
            Entry::Lighting => lighting_label(shown.lighting),
            Entry::Map => shown.map,
            Entry::Fly => on_off(shown.fly),
            Entry::Run => on_off(shown.run),
            Entry::Textures => shown.textures.label(),
            Entry::Preprocessing => shown.preprocessing.label(),
            // Not offered at 120 wide, where floors already have one texel per halfword.
            Entry::Floors if !Floors::offered_at(shown.resolution) => "-",
            Entry::Floors => shown.floors.label(),
            Entry::Hud => on_off(shown.hud),
            Entry::Things => shown.things.label(),
        }
    }
}

/// The menu's lines for `shown`, with the cursor on entry `cursor`.
pub fn text(cursor: usize, shown: &Shown) -> MenuText {
    let mut lines = [Line::blank(); PANEL_LINES];
    lines[0].put(0, "MENU START:BACK");
    for (index, entry) in ENTRIES.iter().enumerate() {
        lines[index + 1] = Line::entry(index == cursor, entry.label(), entry.value(shown));
    }
    lines
}

/// Whether the menu is open, and the entry under the cursor.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Menu {
    /// Shown, and the game paused.
    pub open: bool,
    /// Index into [`ENTRIES`].
    pub cursor: usize,
}

/// The palette indices the menu is drawn with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MenuColours {
    /// The panel.
    pub background: u8,
    /// Text.
    pub text: u8,
}

impl MenuColours {
    /// The darkest and the brightest colour of `palette` (BGR555; index 0, transparent, is
    /// left out).
    pub fn from_palette(palette: &[u16; 256]) -> MenuColours {
        let luma = |colour: u16| {
            let (r, g, b) = (colour & 31, (colour >> 5) & 31, (colour >> 10) & 31);
            u32::from(r) * 2 + u32::from(g) * 4 + u32::from(b)
        };
        let mut colours = MenuColours {
            background: 1,
            text: 1,
        };
        for index in 1..=255u8 {
            let here = luma(palette[usize::from(index)]);
            if here < luma(palette[usize::from(colours.background)]) {
                colours.background = index;
            }
            if here > luma(palette[usize::from(colours.text)]) {
                colours.text = index;
            }
        }
        colours
    }
}

/// Horizontal advance per character (one column of space).
const ADVANCE: usize = GLYPH_WIDTH + 1;
/// Vertical advance per line.
const LINE_HEIGHT: usize = GLYPH_HEIGHT + 1;
/// Characters per menu line: the cursor, the label (6 wide) and the value.
pub const LINE_CHARS: usize = 15;
/// Room around the text, in font pixels.
const PADDING: usize = 2;
/// The panel in font pixels (one font pixel is 2×2 screen pixels: the screen is 120×80 of them).
const PANEL_WIDTH: usize = 2 * PADDING + LINE_CHARS * ADVANCE - 1;
const PANEL_LINES: usize = 1 + ENTRIES.len();
const PANEL_HEIGHT: usize = 2 * PADDING + PANEL_LINES * LINE_HEIGHT - 1;
const PANEL_LEFT: usize = (120 - PANEL_WIDTH) / 2;
const PANEL_TOP: usize = (80 - PANEL_HEIGHT) / 2;
const _: () = assert!(PANEL_WIDTH <= 64, "a panel row is a u64 bit mask");
const _: () = assert!(PANEL_LEFT + PANEL_WIDTH <= 120 && PANEL_TOP + PANEL_HEIGHT <= 80);

/// One line of text: up to [`LINE_CHARS`] characters, lower case shown as upper case.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Line {
    chars: [u8; LINE_CHARS],
}

impl Line {
    /// A line of spaces.
    pub const fn blank() -> Line {
        Line {
            chars: [b' '; LINE_CHARS],
        }
    }

    /// Writes `text` from character `column` on (cut at the end of the line).
    pub fn put(&mut self, column: usize, text: &str) {
        for (slot, byte) in self.chars.iter_mut().skip(column).zip(text.bytes()) {
            *slot = byte.to_ascii_uppercase();
        }
    }

    /// The entry line: the cursor mark, the label, the value at column 8.
    pub fn entry(selected: bool, label: &str, value: &str) -> Line {
        let mut line = Line::blank();
        if selected {
            line.put(0, ">");
        }
        line.put(2, label);
        line.put(8, value);
        line
    }

    /// Whether font pixel (`x`, `row`) of the line is lit.
    fn lit(&self, x: usize, row: usize) -> bool {
        let (column, within) = (x / ADVANCE, x % ADVANCE);
        column < LINE_CHARS && glyph_lit(self.chars[column], within, row)
    }
}

/// The menu's text: a title line and one line per entry.
pub type MenuText = [Line; PANEL_LINES];

/// Draws the menu panel with `text` over whatever `canvas` holds, every pixel of the panel
/// exactly once.
pub fn draw(canvas: &mut impl Canvas, text: &MenuText, colours: MenuColours) {
    draw_panel(canvas, text, (PANEL_LEFT, PANEL_TOP), colours);
}

/// Draws a panel of `lines` with its top-left corner at font pixel `(left, top)`.
fn draw_panel(
    canvas: &mut impl Canvas,
    lines: &[Line],
    (left, top): (usize, usize),
    colours: MenuColours,
) {
    let resolution = canvas.resolution();
    let solid = |index: u8| [index; 64];
    let background = solid(colours.background);
    let foreground = solid(colours.text);
    let height = 2 * PADDING + lines.len() * LINE_HEIGHT - 1;
    for panel_row in 0..height {
        let mask = row_mask(lines, panel_row);
        // Runs of equal colour along the row, in font pixels.
        let mut start = 0;
        while start < PANEL_WIDTH {
            let lit = mask >> start & 1 != 0;
            let mut end = start + 1;
            while end < PANEL_WIDTH && (mask >> end & 1 != 0) == lit {
                end += 1;
            }
            let texels = if lit { &foreground } else { &background };
            fill(
                canvas,
                resolution,
                (left + start, left + end),
                top + panel_row,
                texels,
            );
            start = end;
        }
    }
}

/// The heads-up display's one line: the frame rate the last frame's cycles imply (tenths) and
/// those cycles in thousands, e.g. `20.6FPS 815K`.
pub fn hud_line(render_cycles: u32) -> Line {
    let cycles = render_cycles.max(1);
    // The CPU runs 2^24 cycles a second; a frame shown takes whole VBlank periods, but the HUD
    // reports what the drawing alone would allow, as docs/BENCH.md does.
    let tenths_of_fps = (10u64 << 24) / u64::from(cycles);
    let mut text = [b' '; LINE_CHARS];
    let mut at = 0;
    let mut push = |bytes: &[u8]| {
        for &byte in bytes {
            if at < LINE_CHARS {
                text[at] = byte;
                at += 1;
            }
        }
    };
    let mut digits = [0u8; 10];
    let mut number = |value: u64, push: &mut dyn FnMut(&[u8])| {
        let mut count = 0;
        let mut rest = value;
        loop {
            digits[count] = b'0' + (rest % 10) as u8;
            count += 1;
            rest /= 10;
            if rest == 0 {
                break;
            }
        }
        digits[..count].reverse();
        push(&digits[..count]);
    };
    number(tenths_of_fps / 10, &mut push);
    push(b".");
    number(tenths_of_fps % 10, &mut push);
    push(b"FPS ");
    number(u64::from(cycles).div_ceil(1000), &mut push);
    push(b"K");
    let mut line = Line::blank();
    line.chars = text;
    line
}

/// Draws the heads-up display (one [`hud_line`]) in the top-left corner.
pub fn draw_hud(canvas: &mut impl Canvas, line: &Line, colours: MenuColours) {
    draw_panel(canvas, core::slice::from_ref(line), (0, 0), colours);
}

/// The lit font pixels of one panel row, bit `x` for column `x`.
fn row_mask(text: &[Line], panel_row: usize) -> u64 {
    let Some(y) = panel_row.checked_sub(PADDING) else {
        return 0;
    };
    let (line, row) = (y / LINE_HEIGHT, y % LINE_HEIGHT);
    let Some(line) = text.get(line) else {
        return 0;
    };
    let mut mask = 0u64;
    for x in 0..PANEL_WIDTH.saturating_sub(PADDING) {
        if line.lit(x, row) {
            mask |= 1 << (x + PADDING);
        }
    }
    mask
}

/// Fills font-pixel columns `[from, to)` of font-pixel row `row` with one colour, at the
/// canvas's resolution (a font pixel is `width/120 × height/80` logical pixels).
fn fill(
    canvas: &mut impl Canvas,
    resolution: Resolution,
    (from, to): (usize, usize),
    row: usize,
    texels: &[u8; 64],
) {
    let sx = resolution.width() / 120;
    let sy = resolution.height() / 80;
    let flat = FlatTexture {
        texels,
        log2_side: 3,
        pos: PackedUv(0),
        step: PackedUv(0),
        colormap: None,
    };
    for logical_row in row * sy..(row + 1) * sy {
        canvas.flat(logical_row, from * sx, (to - from) * sx, &flat);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use portalcast::text::glyph;

    #[test]
    fn the_hud_line_shows_the_rate_and_the_cycles() {
        let text = |cycles| {
            let line = hud_line(cycles);
            String::from_utf8(line.chars.to_vec()).unwrap()
        };
        // 2^24 / 280,896 = 59.7 frames a second.
        assert_eq!(text(280_896).trim_end(), "59.7FPS 281K");
        assert_eq!(text(815_536).trim_end(), "20.5FPS 816K");
        // Never a division by zero, never past the line.
        assert_eq!(text(0).len(), LINE_CHARS);
        assert_eq!(text(u32::MAX).trim_end(), "0.0FPS 4294968K");
    }

    #[test]
    fn every_character_the_menu_writes_has_its_own_glyph() {
        let fallback = glyph(b'\x01');
        for c in b"0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ>:-._?" {
            assert_ne!(glyph(*c), fallback, "{}", *c as char);
        }
        let mut seen = std::collections::BTreeSet::new();
        for c in b"0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ" {
            assert!(seen.insert(glyph(*c)), "{} looks like another", *c as char);
        }
    }
}
