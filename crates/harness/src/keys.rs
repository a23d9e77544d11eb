//! GBA buttons and key scripts (which buttons are held on which frame).

use std::fmt;
use std::ops::{BitAnd, BitOr, BitOrAssign, RangeInclusive};
use std::path::Path;
use std::str::FromStr;

use crate::HarnessError;

/// A set of GBA buttons, in the bit order of the KEYINPUT register (but 1 = held, unlike the
/// hardware, where 0 = pressed).
///
/// Combine with `|`: `Keys::UP | Keys::L`. Any combination reaches the ROM as given, including
/// opposite directions (LEFT+RIGHT, UP+DOWN) that a real d-pad cannot press: the harness's mGBA
/// core is not configured to filter them, so keep scripts physically plausible.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Keys(u16);

impl Keys {
    /// No button held.
    pub const NONE: Keys = Keys(0);
    /// The A button.
    pub const A: Keys = Keys(1 << 0);
    /// The B button.
    pub const B: Keys = Keys(1 << 1);
    /// SELECT.
    pub const SELECT: Keys = Keys(1 << 2);
    /// START.
    pub const START: Keys = Keys(1 << 3);
    /// D-pad right.
    pub const RIGHT: Keys = Keys(1 << 4);
    /// D-pad left.
    pub const LEFT: Keys = Keys(1 << 5);
    /// D-pad up.
    pub const UP: Keys = Keys(1 << 6);
    /// D-pad down.
    pub const DOWN: Keys = Keys(1 << 7);
    /// Right shoulder button.
    pub const R: Keys = Keys(1 << 8);
    /// Left shoulder button.
    pub const L: Keys = Keys(1 << 9);
    /// Every button.
    pub const ALL: Keys = Keys(0x3FF);

    /// Names as a key script writes them, in bit order.
    const NAMES: [(&'static str, Keys); 10] = [
        ("A", Keys::A),
        ("B", Keys::B),
        ("SELECT", Keys::SELECT),
        ("START", Keys::START),
        ("RIGHT", Keys::RIGHT),
        ("LEFT", Keys::LEFT),
        ("UP", Keys::UP),
        ("DOWN", Keys::DOWN),
        ("R", Keys::R),
        ("L", Keys::L),
    ];

    /// The set as KEYINPUT-ordered bits (1 = held).
    pub const fn bits(self) -> u16 {
        self.0
    }

    /// The set with these bits; `None` if a bit above L (bit 9) is set.
    pub const fn from_bits(bits: u16) -> Option<Keys> {
        if bits & !Keys::ALL.0 == 0 {
            Some(Keys(bits))
        } else {
            None
        }
    }

    /// The set with these bits, ignoring bits above L (bit 9).
    pub const fn from_bits_truncate(bits: u16) -> Keys {
        Keys(bits & Keys::ALL.0)
    }

    /// The hardware KEYINPUT value for this set (0 = pressed), as the ROM reads it.
    pub const fn keyinput(self) -> u16 {
        !self.0 & Keys::ALL.0
    }

    /// True if no button is held.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// True if every button of `other` is in `self`.
    pub const fn contains(self, other: Keys) -> bool {
        self.0 & other.0 == other.0
    }

    /// Adds the buttons of `other`.
    pub fn insert(&mut self, other: Keys) {
        self.0 |= other.0;
    }

    /// Removes the buttons of `other`.
    pub fn remove(&mut self, other: Keys) {
        self.0 &= !other.0;
    }

    /// The button with this name (`A`, `B`, `SELECT`, `START`, `RIGHT`, `LEFT`, `UP`, `DOWN`,
    /// `R`, `L`), case-insensitively.
    pub fn from_name(name: &str) -> Option<Keys> {
        Keys::NAMES
            .iter()
            .find(|(known, _)| known.eq_ignore_ascii_case(name))
            .map(|&(_, keys)| keys)
    }
}

impl BitOr for Keys {
    type Output = Keys;
    fn bitor(self, rhs: Keys) -> Keys {
        Keys(self.0 | rhs.0)
    }
}

impl BitOrAssign for Keys {
    fn bitor_assign(&mut self, rhs: Keys) {
        self.0 |= rhs.0;
    }
}

impl BitAnd for Keys {
    type Output = Keys;
    fn bitand(self, rhs: Keys) -> Keys {
        Keys(self.0 & rhs.0)
    }
}

/// Writes the set as a key script would: `UP+L`, or `NONE`.
impl fmt::Display for Keys {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_empty() {
            return f.write_str("NONE");
        }
        let mut first = true;
        for (name, key) in Keys::NAMES {
            if self.contains(key) {
                if !first {
                    f.write_str("+")?;
                }
                f.write_str(name)?;
                first = false;
            }
        }
        Ok(())
    }
}

impl fmt::Debug for Keys {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Keys({self})")
    }
}

/// Parses `UP+L`, `a + start`, or `NONE` (see [`Keys::from_name`] for the names).
impl FromStr for Keys {
    type Err = String;

    fn from_str(text: &str) -> Result<Keys, String> {
        let text = text.trim();
        if text.is_empty() {
            return Err("no keys given (write NONE to hold nothing)".to_owned());
        }
        if text.eq_ignore_ascii_case("NONE") {
            return Ok(Keys::NONE);
        }
        let mut keys = Keys::NONE;
        for name in text.split('+') {
            let name = name.trim();
            match Keys::from_name(name) {
                Some(key) => keys |= key,
                None if name.is_empty() => return Err(format!("empty key name in `{text}`")),
                None => {
                    return Err(format!(
                        "unknown key `{name}` (expected A, B, SELECT, START, RIGHT, LEFT, UP, \
                         DOWN, R, L or NONE)"
                    ))
                }
            }
        }
        Ok(keys)
    }
}

/// A syntax error in a key script, with the 1-based line it was found on.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct KeyScriptError {
    /// 1-based line number in the script text.
    pub line: usize,
    /// What is wrong with that line.
    pub message: String,
}

impl fmt::Display for KeyScriptError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "key script line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for KeyScriptError {}

/// One "hold these keys on these frames" rule; `last: None` means until the end of the run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Hold {
    first: u32,
    last: Option<u32>,
    keys: Keys,
}

/// Which keys are held on each frame of a run, for [`crate::Emulator::run_script`].
///
/// Frames are counted from 0, the first frame the run emulates. A frame that no rule mentions
/// holds nothing; where rules overlap their keys add up.
///
/// # Text syntax
///
/// One rule per line; blank lines and everything after `#` are ignored:
///
/// ```text
/// # frame: keys
/// 10: A            # frame 10 only
/// 20-30: UP+L      # frames 20 to 30, both included
/// 40-: START       # frame 40 to the end of the run
/// ```
///
/// Keys are `A B SELECT START RIGHT LEFT UP DOWN R L` joined by `+`, case-insensitive, spaces
/// allowed; `NONE` holds nothing (handy to document a pause). A bad line is a [`KeyScriptError`]
/// naming its line number.
///
/// The same script in code:
///
/// ```
/// use portalcast_harness::{KeyScript, Keys};
/// let script = KeyScript::new()
///     .hold(10..=10, Keys::A)
///     .hold(20..=30, Keys::UP | Keys::L)
///     .hold_from(40, Keys::START);
/// assert_eq!(script, "10: A\n20-30: UP+L\n40-: START\n".parse().unwrap());
/// ```
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct KeyScript {
    holds: Vec<Hold>,
}

impl KeyScript {
    /// A script that holds nothing on every frame.
    pub fn new() -> KeyScript {
        KeyScript::default()
    }

    /// Adds a rule: hold `keys` on every frame of `frames` (both ends included).
    pub fn hold(mut self, frames: RangeInclusive<u32>, keys: Keys) -> KeyScript {
        self.holds.push(Hold {
            first: *frames.start(),
            last: Some(*frames.end()),
            keys,
        });
        self
    }

    /// Adds a rule: hold `keys` from frame `first` to the end of the run.
    pub fn hold_from(mut self, first: u32, keys: Keys) -> KeyScript {
        self.holds.push(Hold {
            first,
            last: None,
            keys,
        });
        self
    }

    /// The script that holds, from each `(frame, keys)` change on, those keys until the next
    /// change (the last until the end of the run). Changes must come in frame order.
    ///
    /// This replays a recording: the portalcast ROM logs `input vblank=K keys=0x…` whenever the
    /// buttons it samples at VBlank `K` differ from the previous sample, and the sample of
    /// VBlank `K` holds the keys of frame `K + 1`, so [`KeyScript::from_rom_log`] passes the
    /// changes at frames `K + 1`.
    pub fn from_changes(changes: impl IntoIterator<Item = (u32, Keys)>) -> KeyScript {
        let mut script = KeyScript::new();
        let mut current: Option<(u32, Keys)> = None;
        for (frame, keys) in changes {
            if let Some((first, held)) = current.take() {
                if frame > first && !held.is_empty() {
                    script = script.hold(first..=frame - 1, held);
                }
            }
            current = Some((frame, keys));
        }
        if let Some((first, held)) = current {
            if !held.is_empty() {
                script = script.hold_from(first, held);
            }
        }
        script
    }

    /// The key script that replays the buttons a portalcast ROM recorded in its log: its
    /// `input vblank=K keys=0x…` lines (other lines are skipped), see
    /// [`KeyScript::from_changes`], and its `input boot keys=0x… released_vblank=K` line if it
    /// has one: the keys held at power-on that switched the ROM's per-frame lines on. The ROM
    /// waited for them to be let go and the sample of VBlank `K` was the first without them, so
    /// they are held on frames `0..=K` (the sample of VBlank `K` holds frame `K + 1`'s keys).
    pub fn from_rom_log<'a>(lines: impl IntoIterator<Item = &'a str>) -> KeyScript {
        let field = |line: &'a str, key: &str| {
            line.split_whitespace()
                .find_map(|word| word.strip_prefix(key)?.strip_prefix('='))
        };
        let keys_of = |line: &'a str| {
            u16::from_str_radix(field(line, "keys")?.strip_prefix("0x")?, 16)
                .ok()
                .map(Keys::from_bits_truncate)
        };
        let mut boot = None;
        let mut changes = Vec::new();
        for line in lines {
            if let Some(rest) = line.strip_prefix("input boot ") {
                let released: Option<u32> =
                    field(rest, "released_vblank").and_then(|v| v.parse().ok());
                boot = released.zip(keys_of(rest));
            } else if let Some(rest) = line.strip_prefix("input ") {
                let vblank: Option<u32> = field(rest, "vblank").and_then(|v| v.parse().ok());
                if let Some((vblank, keys)) = vblank.zip(keys_of(rest)) {
                    changes.push((vblank + 1, keys));
                }
            }
        }
        let script = KeyScript::from_changes(changes);
        match boot {
            Some((released, keys)) if !keys.is_empty() => script.hold(0..=released, keys),
            _ => script,
        }
    }

    /// The keys held on `frame` (0 = the first frame of the run).
    pub fn keys_at(&self, frame: u32) -> Keys {
        self.holds
            .iter()
            .filter(|hold| frame >= hold.first && hold.last.is_none_or(|last| frame <= last))
            .fold(Keys::NONE, |held, hold| held | hold.keys)
    }

    /// Parses the text syntax described on [`KeyScript`].
    pub fn parse(text: &str) -> Result<KeyScript, KeyScriptError> {
        let mut script = KeyScript::new();
        for (index, raw) in text.lines().enumerate() {
            let line = index + 1;
            let content = raw.split('#').next().unwrap_or("").trim();
            if content.is_empty() {
                continue;
            }
            let hold = parse_rule(content).map_err(|message| KeyScriptError { line, message })?;
            script.holds.push(hold);
        }
        Ok(script)
    }

    /// Reads and parses a key script file.
    pub fn load(path: &Path) -> Result<KeyScript, HarnessError> {
        let text = std::fs::read_to_string(path).map_err(|source| HarnessError::Io {
            path: path.to_owned(),
            action: "read the key script",
            source,
        })?;
        KeyScript::parse(&text).map_err(|source| HarnessError::KeyScript {
            path: path.to_owned(),
            source,
        })
    }
}

impl FromStr for KeyScript {
    type Err = KeyScriptError;
    fn from_str(text: &str) -> Result<KeyScript, KeyScriptError> {
        KeyScript::parse(text)
    }
}

/// Writes the script back in the text syntax, one rule per line.
impl fmt::Display for KeyScript {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for hold in &self.holds {
            match hold.last {
                Some(last) if last == hold.first => writeln!(f, "{}: {}", hold.first, hold.keys)?,
                Some(last) => writeln!(f, "{}-{}: {}", hold.first, last, hold.keys)?,
                None => writeln!(f, "{}-: {}", hold.first, hold.keys)?,
            }
        }
        Ok(())
    }
}

/// Parses `FRAMES: KEYS` (comment and surrounding blanks already removed).
fn parse_rule(content: &str) -> Result<Hold, String> {
    let (frames, keys) = content.split_once(':').ok_or_else(|| {
        format!("expected `FRAMES: KEYS` (e.g. `20-30: UP+L`), found `{content}`")
    })?;
    let frames = frames.trim();
    let keys: Keys = keys.parse()?;
    let frame_number = |text: &str| -> Result<u32, String> {
        let text = text.trim();
        text.parse::<u32>()
            .map_err(|_| format!("`{text}` is not a frame number (expected e.g. `10` or `20-30`)"))
    };
    let (first, last) = match frames.split_once('-') {
        None => {
            let frame = frame_number(frames)?;
            (frame, Some(frame))
        }
        Some((first, last)) if last.trim().is_empty() => (frame_number(first)?, None),
        Some((first, last)) => (frame_number(first)?, Some(frame_number(last)?)),
    };
    if let Some(last) = last {
        if last < first {
            return Err(format!("frame range {first}-{last} ends before it starts"));
        }
    }
    Ok(Hold { first, last, keys })
}
