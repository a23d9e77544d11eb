//! The engine's one font, 3×5 pixels to a glyph, and a screen of text for when the game cannot
//! go on: the Start menu draws its lines with it, and a panic shows its message with it
//! ([`TextScreen`]; the hardware side is `hw::panic_screen`).

use core::fmt;

/// Width of a glyph in font pixels.
pub const GLYPH_WIDTH: usize = 3;
/// Height of a glyph in font pixels.
pub const GLYPH_HEIGHT: usize = 5;

/// 3×5 glyphs: five rows of three bits, the top row in bits 12–14, the left column the high
/// bit of each row.
pub const fn glyph(c: u8) -> u16 {
    const fn rows(r: [u16; 5]) -> u16 {
        (r[0] << 12) | (r[1] << 9) | (r[2] << 6) | (r[3] << 3) | r[4]
    }
    match c {
        b'0' => rows([0b111, 0b101, 0b101, 0b101, 0b111]),
        b'1' => rows([0b010, 0b110, 0b010, 0b010, 0b111]),
        b'2' => rows([0b111, 0b001, 0b111, 0b100, 0b111]),
        b'3' => rows([0b111, 0b001, 0b111, 0b001, 0b111]),
        b'4' => rows([0b101, 0b101, 0b111, 0b001, 0b001]),
        b'5' => rows([0b111, 0b100, 0b111, 0b001, 0b111]),
        b'6' => rows([0b111, 0b100, 0b111, 0b101, 0b111]),
        b'7' => rows([0b111, 0b001, 0b001, 0b010, 0b010]),
        b'8' => rows([0b111, 0b101, 0b111, 0b101, 0b111]),
        b'9' => rows([0b111, 0b101, 0b111, 0b001, 0b111]),
        b'A' => rows([0b010, 0b101, 0b111, 0b101, 0b101]),
        b'B' => rows([0b110, 0b101, 0b110, 0b101, 0b110]),
        b'C' => rows([0b011, 0b100, 0b100, 0b100, 0b011]),
        b'D' => rows([0b110, 0b101, 0b101, 0b101, 0b110]),
        b'E' => rows([0b111, 0b100, 0b110, 0b100, 0b111]),
        b'F' => rows([0b111, 0b100, 0b110, 0b100, 0b100]),
        b'G' => rows([0b011, 0b100, 0b101, 0b101, 0b011]),
        b'H' => rows([0b101, 0b101, 0b111, 0b101, 0b101]),
        b'I' => rows([0b111, 0b010, 0b010, 0b010, 0b111]),
        b'J' => rows([0b001, 0b001, 0b001, 0b101, 0b010]),
        b'K' => rows([0b101, 0b101, 0b110, 0b101, 0b101]),
        b'L' => rows([0b100, 0b100, 0b100, 0b100, 0b111]),
        b'M' => rows([0b101, 0b111, 0b111, 0b101, 0b101]),
        b'N' => rows([0b110, 0b101, 0b101, 0b101, 0b101]),
        b'O' => rows([0b010, 0b101, 0b101, 0b101, 0b010]),
        b'P' => rows([0b110, 0b101, 0b110, 0b100, 0b100]),
        b'Q' => rows([0b010, 0b101, 0b101, 0b110, 0b011]),
        b'R' => rows([0b110, 0b101, 0b110, 0b101, 0b101]),
        b'S' => rows([0b011, 0b100, 0b010, 0b001, 0b110]),
        b'T' => rows([0b111, 0b010, 0b010, 0b010, 0b010]),
        b'U' => rows([0b101, 0b101, 0b101, 0b101, 0b111]),
        b'V' => rows([0b101, 0b101, 0b101, 0b101, 0b010]),
        b'W' => rows([0b101, 0b101, 0b111, 0b111, 0b101]),
        b'X' => rows([0b101, 0b101, 0b010, 0b101, 0b101]),
        b'Y' => rows([0b101, 0b101, 0b010, 0b010, 0b010]),
        b'Z' => rows([0b111, 0b001, 0b010, 0b100, 0b111]),
        b'>' => rows([0b100, 0b010, 0b001, 0b010, 0b100]),
        b':' => rows([0b000, 0b010, 0b000, 0b010, 0b000]),
        b'-' => rows([0b000, 0b000, 0b111, 0b000, 0b000]),
        b'.' => rows([0b000, 0b000, 0b000, 0b000, 0b010]),
        b'_' => rows([0b000, 0b000, 0b000, 0b000, 0b111]),
        b'?' => rows([0b111, 0b001, 0b010, 0b000, 0b010]),
        b'/' => rows([0b001, 0b001, 0b010, 0b100, 0b100]),
        b'\\' => rows([0b100, 0b100, 0b010, 0b001, 0b001]),
        b',' => rows([0b000, 0b000, 0b000, 0b010, 0b100]),
        b';' => rows([0b000, 0b010, 0b000, 0b010, 0b100]),
        b'(' => rows([0b001, 0b010, 0b010, 0b010, 0b001]),
        b')' => rows([0b100, 0b010, 0b010, 0b010, 0b100]),
        b'[' => rows([0b011, 0b010, 0b010, 0b010, 0b011]),
        b']' => rows([0b110, 0b010, 0b010, 0b010, 0b110]),
        b'{' => rows([0b011, 0b010, 0b110, 0b010, 0b011]),
        b'}' => rows([0b110, 0b010, 0b011, 0b010, 0b110]),
        b'<' => rows([0b001, 0b010, 0b100, 0b010, 0b001]),
        b'=' => rows([0b000, 0b111, 0b000, 0b111, 0b000]),
        b'+' => rows([0b000, 0b010, 0b111, 0b010, 0b000]),
        b'*' => rows([0b000, 0b101, 0b010, 0b101, 0b000]),
        b'!' => rows([0b010, 0b010, 0b010, 0b000, 0b010]),
        b'\'' => rows([0b010, 0b010, 0b000, 0b000, 0b000]),
        b'`' => rows([0b100, 0b010, 0b000, 0b000, 0b000]),
        b'"' => rows([0b101, 0b101, 0b000, 0b000, 0b000]),
        b'#' => rows([0b101, 0b111, 0b101, 0b111, 0b101]),
        b'%' => rows([0b101, 0b001, 0b010, 0b100, 0b101]),
        b'&' => rows([0b010, 0b101, 0b010, 0b101, 0b011]),
        b'|' => rows([0b010, 0b010, 0b010, 0b010, 0b010]),
        b'^' => rows([0b010, 0b101, 0b000, 0b000, 0b000]),
        b'~' => rows([0b000, 0b011, 0b110, 0b000, 0b000]),
        b'$' => rows([0b011, 0b110, 0b010, 0b011, 0b110]),
        b'@' => rows([0b111, 0b101, 0b111, 0b100, 0b011]),
        b' ' => 0,
        // Anything else: a full block, visibly not a letter.
        _ => rows([0b111; 5]),
    }
}

/// The first line of a panic's screen (`hw::panic_screen`); the message follows a blank line.
pub const PANIC_TITLE: &str = "PANIC: THE GAME STOPPED";
/// A panic screen's background (BGR555, palette entry 0): dark red.
pub const PANIC_BACKGROUND: u16 = 0x000c;
/// A panic screen's text (BGR555, palette entry 1): white.
pub const PANIC_TEXT: u16 = 0x7fff;

/// Screen pixels a font pixel takes on a [`TextScreen`], each way: 2, so that a message reads on
/// a GBA's screen (the menu's text is as large, through the 120×80 frame's 2×2 scaling).
pub const SCREEN_SCALE: usize = 2;
/// Screen pixels from one character to the next on a [`TextScreen`].
pub const CELL_WIDTH: usize = (GLYPH_WIDTH + 1) * SCREEN_SCALE;
/// Screen pixels from one line to the next on a [`TextScreen`].
pub const CELL_HEIGHT: usize = (GLYPH_HEIGHT + 1) * SCREEN_SCALE;
/// Characters a [`TextScreen`] line holds.
pub const SCREEN_COLUMNS: usize = 240 / CELL_WIDTH;
/// Lines a [`TextScreen`] holds.
pub const SCREEN_LINES: usize = 160 / CELL_HEIGHT;
/// Screen rows above the first line: the lines are centred on the 160-row screen.
const SCREEN_TOP: usize = (160 - SCREEN_LINES * CELL_HEIGHT) / 2;

/// A full 240×160 screen of text, written through [`fmt::Write`]: a line breaks at a newline or
/// after [`SCREEN_COLUMNS`] characters, lower case shows as upper case, and what comes after the
/// last line is dropped. It lives on the stack (390 bytes) and allocates nothing, so a panic
/// handler can fill it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextScreen {
    cells: [[u8; SCREEN_COLUMNS]; SCREEN_LINES],
    column: usize,
    line: usize,
}

impl TextScreen {
    /// A screen of spaces, written from its top-left character on.
    pub const fn new() -> TextScreen {
        TextScreen {
            cells: [[b' '; SCREEN_COLUMNS]; SCREEN_LINES],
            column: 0,
            line: 0,
        }
    }

    /// The characters of line `line` (spaces where nothing was written).
    pub fn line(&self, line: usize) -> &[u8; SCREEN_COLUMNS] {
        &self.cells[line]
    }

    /// Whether screen pixel (`x`, `y`) is lit (text) rather than background.
    pub fn lit(&self, x: usize, y: usize) -> bool {
        let Some(y) = y.checked_sub(SCREEN_TOP) else {
            return false;
        };
        let (line, row) = (y / CELL_HEIGHT, y % CELL_HEIGHT / SCREEN_SCALE);
        let (column, within) = (x / CELL_WIDTH, x % CELL_WIDTH / SCREEN_SCALE);
        if line >= SCREEN_LINES || column >= SCREEN_COLUMNS {
            return false;
        }
        glyph_lit(self.cells[line][column], within, row)
    }

    fn push(&mut self, byte: u8) {
        if byte == b'\n' {
            self.column = 0;
            self.line += 1;
            return;
        }
        if self.column == SCREEN_COLUMNS {
            self.column = 0;
            self.line += 1;
        }
        if let Some(line) = self.cells.get_mut(self.line) {
            line[self.column] = byte.to_ascii_uppercase();
            self.column += 1;
        }
    }
}

impl Default for TextScreen {
    fn default() -> Self {
        TextScreen::new()
    }
}

impl fmt::Write for TextScreen {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        // A character outside ASCII is one block, not one per byte.
        for c in text.chars() {
            self.push(if c.is_ascii() { c as u8 } else { 0x7f });
        }
        Ok(())
    }
}

/// Whether font pixel (`x`, `row`) of `c`'s glyph is lit; outside the glyph it is not.
pub fn glyph_lit(c: u8, x: usize, row: usize) -> bool {
    if x >= GLYPH_WIDTH || row >= GLYPH_HEIGHT {
        return false;
    }
    let shift = (GLYPH_HEIGHT - 1 - row) * GLYPH_WIDTH + (GLYPH_WIDTH - 1 - x);
    glyph(c) >> shift & 1 != 0
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::fmt::Write;

    #[test]
    fn a_panic_message_wraps_breaks_and_shows_in_capitals() {
        let mut screen = TextScreen::new();
        write!(
            screen,
            "panicked at src/a.rs:1:2:\n{}",
            "x".repeat(SCREEN_COLUMNS + 3)
        )
        .unwrap();
        assert_eq!(&screen.line(0)[..25], b"PANICKED AT SRC/A.RS:1:2:");
        assert_eq!(screen.line(1), &[b'X'; SCREEN_COLUMNS]);
        assert_eq!(&screen.line(2)[..4], b"XXX ");
        assert!(screen.line(3).iter().all(|&c| c == b' '));
    }

    #[test]
    fn text_past_the_last_line_is_dropped() {
        let mut screen = TextScreen::new();
        for line in 0..SCREEN_LINES + 5 {
            writeln!(screen, "{line}").unwrap();
        }
        let last = format!("{} ", SCREEN_LINES - 1);
        assert_eq!(
            &screen.line(SCREEN_LINES - 1)[..last.len()],
            last.as_bytes()
        );
    }

    #[test]
    fn the_screen_lights_a_glyph_scaled_at_its_cell() {
        let mut screen = TextScreen::new();
        screen.write_str("-").unwrap();
        // '-' lights its middle row: font row 2 of cell (0, 0).
        let y = SCREEN_TOP + 2 * SCREEN_SCALE;
        assert!(screen.lit(0, y) && screen.lit(5, y + 1));
        assert!(!screen.lit(6, y), "the space between characters");
        assert!(!screen.lit(0, y - 1));
        assert!(!screen.lit(0, 0));
    }

    #[test]
    fn the_punctuation_of_panic_messages_has_glyphs_of_its_own() {
        let block = glyph(0x7f);
        let mut seen = std::collections::BTreeMap::new();
        for c in b"0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ>:-._?/\\,;()[]{}<=+*!'`\"#%&|^~$@".iter() {
            assert_ne!(glyph(*c), block, "{}", *c as char);
            if let Some(other) = seen.insert(glyph(*c), *c) {
                panic!("{} looks like {}", *c as char, other as char);
            }
        }
    }
}
