//! Line tokens and number syntax shared by the `.map` and `.grid` parsers.

use portalcast_format::limits::{HEIGHT_DIFF_MAX, WORLD_COORD_MAX};
use portalcast_format::{
    LIGHT_FLICKER, LIGHT_GLOW, LIGHT_STROBE, LIGHT_SWITCHED, STROBE_FLASH_TICKS,
};

use crate::diag::{Loc, Located};
use crate::source::{
    MoverKind, SourceLight, SourceMover, Spanned, ThingOptions, DEFAULT_FRAME_TICKS,
};

/// A whitespace-separated word of a line and where it starts.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Token<'t> {
    pub text: &'t str,
    pub loc: Loc,
}

/// Splits a line into tokens (any Unicode whitespace separates), with 1-based character columns.
pub(crate) fn tokens(line: &str, line_no: u32) -> Vec<Token<'_>> {
    let mut out = Vec::new();
    let mut start: Option<(usize, u32)> = None;
    let mut col = 0u32;
    for (byte, ch) in line.char_indices() {
        col += 1;
        match (ch.is_whitespace(), start) {
            (true, Some((s, c))) => {
                out.push(Token {
                    text: &line[s..byte],
                    loc: Loc::new(line_no, c),
                });
                start = None;
            }
            (false, None) => start = Some((byte, col)),
            _ => {}
        }
    }
    if let Some((s, c)) = start {
        out.push(Token {
            text: &line[s..],
            loc: Loc::new(line_no, c),
        });
    }
    out
}

/// The `key=value` words of a directive, checked for duplicates, taken one by one by the parser;
/// whatever is left is an unknown key.
pub(crate) struct KeyValues<'t> {
    pairs: Vec<(Token<'t>, Token<'t>, bool)>,
}

impl<'t> KeyValues<'t> {
    /// Splits `words` into positional words (before the first `key=value`) and key/value pairs.
    pub fn split(
        words: &[Token<'t>],
        errors: &mut Vec<Located>,
    ) -> (Vec<Token<'t>>, KeyValues<'t>) {
        let mut positional = Vec::new();
        let mut pairs: Vec<(Token<'t>, Token<'t>, bool)> = Vec::new();
        for word in words {
            let Some((key, value)) = word.text.split_once('=') else {
                if pairs.is_empty() {
                    positional.push(*word);
                } else {
                    errors.push((
                        word.loc,
                        format!(
                            "'{}' after key=value settings; put plain values before the settings",
                            word.text
                        ),
                    ));
                }
                continue;
            };
            let value_loc = Loc::new(word.loc.line, word.loc.col + key.chars().count() as u32 + 1);
            if key.is_empty() || value.is_empty() {
                errors.push((
                    word.loc,
                    format!(
                        "'{}' is not a key=value setting; write it as key=value with no spaces",
                        word.text
                    ),
                ));
                continue;
            }
            if pairs.iter().any(|(k, _, _)| k.text == key) {
                errors.push((word.loc, format!("'{key}' is set twice; keep one")));
                continue;
            }
            pairs.push((
                Token {
                    text: key,
                    loc: word.loc,
                },
                Token {
                    text: value,
                    loc: value_loc,
                },
                false,
            ));
        }
        (positional, KeyValues { pairs })
    }

    /// Whether the directive sets `key`, without marking it as known.
    pub fn has(&self, key: &str) -> bool {
        self.pairs.iter().any(|(k, _, _)| k.text == key)
    }

    /// The value of `key`, marking it as known.
    pub fn take(&mut self, key: &str) -> Option<Token<'t>> {
        self.pairs
            .iter_mut()
            .find(|(k, _, _)| k.text == key)
            .map(|pair| {
                pair.2 = true;
                pair.1
            })
    }

    /// Reports every key not taken, listing the keys the directive accepts.
    pub fn report_unknown(&self, directive: &str, accepted: &[&str], errors: &mut Vec<Located>) {
        for (key, _, taken) in &self.pairs {
            if !taken {
                errors.push((
                    key.loc,
                    format!(
                        "unknown key '{}' for {directive}; accepted keys: {}",
                        key.text,
                        accepted.join(", ")
                    ),
                ));
            }
        }
    }
}

/// The bare words a `thing` line may carry after its position, in any order among its settings.
pub(crate) const THING_FLAGS: &[&str] = &["hang", "solid", "translucent"];

/// The bare words a `wall` line of a `.map` may carry after its two vertices.
pub(crate) const WALL_FLAGS: &[&str] = &["blocks", "translucent"];

/// The bare words a `sector` line of a `.map` may carry after its name: a door, and how movers
/// start.
pub(crate) const SECTOR_FLAGS: &[&str] = &["door", "touch", "locked"];

/// Fastest `speed=`: world units a mover's plane moves a tick.
pub(crate) const MOVER_SPEED_MAX: i64 = 64;

/// Largest `tag=` (of a mover, a switched light or a switch) and `trigger=`; tag 0 means none.
pub(crate) const TAG_MAX: i64 = u16::MAX as i64;

/// Parses a tag (`tag=N`, `trigger=N`): 1 ..= [`TAG_MAX`].
pub(crate) fn tag(token: Token<'_>, what: &str) -> Result<Spanned<u16>, Located> {
    integer_in(token, what, 1, TAG_MAX).map(|value| Spanned::new(value as u16, token.loc))
}

/// The mover of a sector line: its mover word (the bare word `door`, or `lift=`, `platform=`,
/// `crusher=` taken from `keys`), the words `touch` and `locked` (among `flags`, from
/// [`split_flags`]) and the settings `speed=`, `wait=`, `tag=`. `Some(None)` for a sector that
/// does not move, `None` if something is wrong (each error reported once, at its word).
///
/// `tag_token` is the line's `tag=` and `tag` its value parsed (the caller takes and parses it:
/// a switched light uses it too), and `switched` whether the line has a switched light, which
/// makes `tag=` without a mover right.
pub(crate) fn mover_options(
    flags: &[Token<'_>],
    keys: &mut KeyValues<'_>,
    (tag_token, tag): (Option<Token<'_>>, Option<Spanned<u16>>),
    switched: bool,
    errors: &mut Vec<Located>,
) -> Option<Option<SourceMover>> {
    let flag = |word: &str| flags.iter().find(|f| f.text == word).map(|f| f.loc);
    // Every mover word written, in the order written.
    let mut words: Vec<(MoverKind, &str, Loc, Option<Token<'_>>)> = Vec::new();
    if let Some(loc) = flag("door") {
        words.push((MoverKind::Door, "door", loc, None));
    }
    for (kind, key) in [
        (MoverKind::Lift, "lift="),
        (MoverKind::Platform, "platform="),
        (MoverKind::Crusher, "crusher="),
    ] {
        if let Some(token) = keys.take(key.trim_end_matches('=')) {
            words.push((kind, key, token.loc, Some(token)));
        }
    }
    words.sort_by_key(|word| word.2);
    let before = errors.len();
    for extra in words.iter().skip(1) {
        errors.push((
            extra.2,
            format!(
                "'{}' after '{}': a sector moves one way; keep one of door, lift=LOW, platform=OTHER, crusher=LOW",
                extra.1, words[0].1
            ),
        ));
    }
    let speed = keys.take("speed");
    let wait = keys.take("wait");
    let (touch, locked) = (flag("touch"), flag("locked"));
    let Some(&(kind, _, loc, height)) = words.first() else {
        for (key, token) in [("speed", speed), ("wait", wait)] {
            if let Some(token) = token {
                errors.push((
                    token.loc,
                    format!(
                        "{key}= applies to a moving sector; add a mover word (door, lift=LOW, platform=OTHER, crusher=LOW) or remove {key}="
                    ),
                ));
            }
        }
        if let Some(token) = tag_token.filter(|_| !switched) {
            errors.push((
                token.loc,
                "tag= applies to a moving sector or a switched light; add a mover word (door, lift=LOW, platform=OTHER, crusher=LOW) or switched=LOW, or remove tag=".to_string(),
            ));
        }
        if let Some(at) = touch {
            errors.push((
                at,
                "'touch' applies to a door (it opens when the player walks into it); add the word door, or remove touch".to_string(),
            ));
        }
        if let Some(at) = locked {
            errors.push((
                at,
                "'locked' applies to a door or a lift (only a switch or line with its tag starts it); add door or lift=LOW, or remove locked".to_string(),
            ));
        }
        return (errors.len() == before).then_some(None);
    };
    if let Some(at) = touch {
        if kind != MoverKind::Door {
            errors.push((
                at,
                format!(
                    "'touch' applies to doors only, and this sector is a {}; remove touch",
                    kind.name()
                ),
            ));
        } else if locked.is_some() {
            errors.push((
                at,
                "'touch' opens the door when the player walks into it, 'locked' says only a switch or line with its tag does; keep one".to_string(),
            ));
        }
    }
    if let Some(at) = locked {
        if !matches!(kind, MoverKind::Door | MoverKind::Lift) {
            errors.push((
                at,
                format!(
                    "'locked' applies to doors and lifts only: a {} moves from the start, without being started; remove locked",
                    kind.name()
                ),
            ));
        } else if tag_token.is_none() {
            errors.push((
                at,
                format!(
                    "a locked {} needs tag=N: only a switch (switch=TEX tag=N) or a line (trigger=N) with that tag starts it; add tag=N",
                    kind.name()
                ),
            ));
        }
    }
    let (default_speed, default_wait) = kind.defaults();
    let mut number = |token: Option<Token<'_>>, what: &str, min: i64, max: i64, default: u16| {
        token.map_or(default, |t| match integer_in(t, what, min, max) {
            Ok(value) => value as u16,
            Err(e) => {
                errors.push(e);
                default
            }
        })
    };
    let speed = number(speed, "speed", 1, MOVER_SPEED_MAX, default_speed);
    let wait = number(wait, "wait", 0, i64::from(u16::MAX), default_wait);
    let height = height.and_then(|t| {
        integer(t, &format!("{} height", kind.name()))
            .map(|value| Spanned::new(value, t.loc))
            .map_err(|e| errors.push(e))
            .ok()
    });
    let mover = SourceMover {
        kind,
        loc,
        height,
        touch: touch.is_some(),
        locked,
        speed,
        wait,
        tag,
    };
    (errors.len() == before).then_some(Some(mover))
}

/// The light effect words of a sector line (`glow=LOW`, ...) and the [`Light::kind`] each
/// gives.
///
/// [`Light::kind`]: portalcast_format::Light::kind
const LIGHT_WORDS: [(&str, u8); 4] = [
    ("glow", LIGHT_GLOW),
    ("strobe", LIGHT_STROBE),
    ("flicker", LIGHT_FLICKER),
    ("switched", LIGHT_SWITCHED),
];

/// Shortest `period=` of a glow and a flicker, ticks: a glow needs a tick down and a tick up.
const PERIOD_MIN: i64 = 2;

/// `period=` of a glow, a strobe and a flicker when the sector gives none, ticks: a glow's
/// two-second breath, Doom's slow strobe (5 ticks lit, 35 dark), a flicker drawn every 4.
fn default_period(kind: u8) -> u16 {
    match kind {
        LIGHT_GLOW => 120,
        LIGHT_STROBE => 40,
        LIGHT_FLICKER => 4,
        _ => 0,
    }
}

/// The light effect of a sector line: its word (`glow=LOW`, `strobe=LOW`, `flicker=LOW`,
/// `switched=LOW`, taken from `keys`) and `period=`. `tag_token` is the line's `tag=` and `tag`
/// its value parsed (the caller takes and parses it once: a mover uses it too); a switched
/// light needs it. `Some(None)` for a sector whose light stays, `None` if something is wrong
/// (each error reported once, at its word). The low level is checked against the sector's
/// light by `map_build`, which knows both.
pub(crate) fn light_options(
    keys: &mut KeyValues<'_>,
    (tag_token, tag): (Option<Token<'_>>, Option<Spanned<u16>>),
    errors: &mut Vec<Located>,
) -> Option<Option<SourceLight>> {
    // Every effect word written, in the order written: the first is the effect, the others
    // are errors.
    let mut words: Vec<(&'static str, u8, Token<'_>)> = LIGHT_WORDS
        .iter()
        .filter_map(|&(word, kind)| Some((word, kind, keys.take(word)?)))
        .collect();
    words.sort_by_key(|word| word.2.loc);
    let before = errors.len();
    for extra in words.iter().skip(1) {
        errors.push((
            extra.2.loc,
            format!(
                "'{}=' after '{}=': a sector has one light effect; keep one of glow=LOW, strobe=LOW, flicker=LOW, switched=LOW",
                extra.0, words[0].0
            ),
        ));
    }
    let period = keys.take("period");
    let Some(&(word, kind, low_token)) = words.first() else {
        if let Some(token) = period {
            errors.push((
                token.loc,
                "period= applies to a light effect; add glow=LOW, strobe=LOW or flicker=LOW, or remove period=".to_string(),
            ));
        }
        return (errors.len() == before).then_some(None);
    };
    let low = integer_in(low_token, &format!("{word} low level"), 0, 255)
        .map(|value| Spanned::new(value as u8, low_token.loc))
        .map_err(|e| errors.push(e))
        .ok();
    let period = match (kind, period) {
        (LIGHT_SWITCHED, Some(token)) => {
            errors.push((
                token.loc,
                "period= applies to a glow, a strobe or a flicker: a switched light changes when a switch or line of its tag fires; remove period=".to_string(),
            ));
            None
        }
        (LIGHT_STROBE, Some(token)) => {
            // The flash must leave some dark in each period, or the strobe would not blink.
            let min = i64::from(STROBE_FLASH_TICKS) + 1;
            integer_in(token, "strobe period", min, i64::from(u16::MAX))
                .map(|value| value as u16)
                .map_err(|(loc, message)| {
                    errors.push((
                        loc,
                        format!("{message} (a strobe is lit {STROBE_FLASH_TICKS} ticks of each period, dark the rest)"),
                    ))
                })
                .ok()
        }
        (_, Some(token)) => integer_in(
            token,
            &format!("{word} period"),
            PERIOD_MIN,
            i64::from(u16::MAX),
        )
        .map(|value| value as u16)
        .map_err(|e| errors.push(e))
        .ok(),
        (_, None) => Some(default_period(kind)),
    };
    let switched = kind == LIGHT_SWITCHED;
    if switched && tag_token.is_none() {
        errors.push((
            low_token.loc,
            "switched= needs tag=N on the same line: the switches and walk-over lines of tag N turn the light down and up; add tag=N".to_string(),
        ));
    }
    let light = SourceLight {
        kind,
        word,
        low: low?,
        period: period?,
        tag: if switched { tag } else { None },
    };
    (errors.len() == before).then_some(Some(light))
}

/// Takes the bare option words (`flags`) out of `words`, the words after a directive's name:
/// only at index `skip` (the first word after its plain values) or later, each at most once.
/// Any other bare word there is unknown. Returns the other words and the flags found.
pub(crate) fn split_flags<'t>(
    words: &[Token<'t>],
    skip: usize,
    flags: &[&str],
    directive: &str,
    keys: &[&str],
    errors: &mut Vec<Located>,
) -> (Vec<Token<'t>>, Vec<Token<'t>>) {
    let mut rest = Vec::new();
    let mut found: Vec<Token<'t>> = Vec::new();
    for (index, word) in words.iter().enumerate() {
        if index < skip || word.text.contains('=') {
            rest.push(*word);
        } else if !flags.contains(&word.text) {
            errors.push((
                word.loc,
                format!(
                    "unknown word '{}' for {directive}; after its values it takes the words {} and the settings {}",
                    word.text,
                    flags.join(", "),
                    keys.iter().map(|k| format!("{k}=")).collect::<Vec<_>>().join(", ")
                ),
            ));
        } else if found.iter().any(|f| f.text == word.text) {
            errors.push((
                word.loc,
                format!("'{}' is given twice; keep one", word.text),
            ));
        } else {
            found.push(*word);
        }
    }
    (rest, found)
}

/// Largest `anim=`: game ticks a frame shows (255 ticks, over 4 seconds).
pub(crate) const FRAME_TICKS_MAX: i64 = 255;

/// The options of a `thing` line: its `flags` (from [`split_flags`]) and its `z=`, `radius=`
/// and `anim=` settings (taken from `keys`), if every value is valid (each bad one is reported).
pub(crate) fn thing_options(
    flags: &[Token<'_>],
    keys: &mut KeyValues<'_>,
    errors: &mut Vec<Located>,
) -> Option<ThingOptions> {
    let z = match keys.take("z") {
        Some(t) => integer_in(t, "z", 0, i64::from(HEIGHT_DIFF_MAX))
            .map_err(|e| errors.push(e))
            .ok(),
        None => Some(0),
    };
    let radius = match keys.take("radius") {
        Some(t) => integer_in(t, "radius", 0, i64::from(WORLD_COORD_MAX))
            .map(|value| Some(Spanned::new(value, t.loc)))
            .map_err(|e| errors.push(e))
            .ok(),
        None => Some(None),
    };
    let frame_ticks = match keys.take("anim") {
        Some(t) => integer_in(t, "anim", 1, FRAME_TICKS_MAX)
            .map(|ticks| ticks as u16)
            .map_err(|e| errors.push(e))
            .ok(),
        None => Some(DEFAULT_FRAME_TICKS),
    };
    let has = |flag: &str| flags.iter().any(|f| f.text == flag);
    Some(ThingOptions {
        z: z?,
        hanging: has("hang"),
        solid: has("solid"),
        translucent: has("translucent"),
        radius: radius?,
        frame_ticks: frame_ticks?,
    })
}

/// Largest magnitude the parsers accept for any integer, far beyond every declared limit, so
/// later arithmetic (i64 / i128) cannot overflow.
const NUMBER_MAGNITUDE_MAX: i64 = 1 << 40;

/// Parses a decimal integer (optional sign).
pub(crate) fn integer(token: Token<'_>, what: &str) -> Result<i64, Located> {
    let digits = token.text.strip_prefix(['-', '+']).unwrap_or(token.text);
    let valid = !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit());
    match token.text.parse::<i64>() {
        // Not `value.abs()`: i64::MIN (`-9223372036854775808`) parses but has no absolute value.
        Ok(value) if valid && value.unsigned_abs() <= NUMBER_MAGNITUDE_MAX as u64 => Ok(value),
        Ok(_) => Err((token.loc, format!("{what} '{}' is far out of range; use a value within the limits in docs/MAP_FORMAT.md", token.text))),
        Err(_) if valid => Err((token.loc, format!("{what} '{}' is far out of range; use a value within the limits in docs/MAP_FORMAT.md", token.text))),
        Err(_) => Err((token.loc, format!("{what} '{}' is not an integer; write digits with an optional '-'", token.text))),
    }
}

/// Parses an integer within `min..=max`.
pub(crate) fn integer_in(token: Token<'_>, what: &str, min: i64, max: i64) -> Result<i64, Located> {
    let value = integer(token, what)?;
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err((
            token.loc,
            format!("{what} {value} is out of range; use {min}..={max}"),
        ))
    }
}

/// A decimal number `[-]digits[.digits]` as `numerator / 10^scale`.
fn decimal(token: Token<'_>, what: &str) -> Result<(i128, u32), Located> {
    let bad = || {
        (
            token.loc,
            format!("{what} '{}' is not a number; write digits with an optional '-' and '.' (e.g. 32.5)", token.text),
        )
    };
    let (negative, body) = match token.text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, token.text.strip_prefix('+').unwrap_or(token.text)),
    };
    let (whole, fraction) = body.split_once('.').unwrap_or((body, ""));
    if whole.is_empty()
        || !whole.bytes().all(|b| b.is_ascii_digit())
        || !fraction.bytes().all(|b| b.is_ascii_digit())
        || (body.contains('.') && fraction.is_empty())
    {
        return Err(bad());
    }
    let whole = whole.trim_start_matches('0');
    if whole.len() > 12 || fraction.len() > 12 {
        return Err((
            token.loc,
            format!(
                "{what} '{}' has too many digits; use at most 12 before and 12 after the '.'",
                token.text
            ),
        ));
    }
    let mut numerator: i128 = 0;
    for b in whole.bytes().chain(fraction.bytes()) {
        numerator = numerator * 10 + i128::from(b - b'0');
    }
    Ok((
        if negative { -numerator } else { numerator },
        fraction.len() as u32,
    ))
}

/// Rounds `n / d` to the nearest integer, halves away from zero (`d > 0`).
pub(crate) fn div_round(n: i128, d: i128) -> i128 {
    if n >= 0 {
        (n + d / 2) / d
    } else {
        -((-n + d / 2) / d)
    }
}

/// Parses a world position as 24.8 fixed point, rounded to the nearest 1/256.
pub(crate) fn position_fx8(token: Token<'_>, what: &str) -> Result<i64, Located> {
    let (numerator, scale) = decimal(token, what)?;
    // At most 24 digits in all, so numerator * 256 fits i128 comfortably.
    Ok(div_round(numerator * 256, 10i128.pow(scale)) as i64)
}

/// Parses an angle in degrees (0 along +x, 90 along +y) into a binary angle, 65536 per turn.
pub(crate) fn angle_degrees(token: Token<'_>) -> Result<u16, Located> {
    let (numerator, scale) = decimal(token, "angle")?;
    let binary = div_round(numerator * 65536, 360 * 10i128.pow(scale));
    Ok(binary.rem_euclid(65536) as u16)
}

/// Whether `name` is a valid vertex, sector, texture or sprite name: letters, digits, `_`, `-`.
pub(crate) fn is_name(name: &str) -> bool {
    !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Checks a name token, reporting what a name may contain.
pub(crate) fn name(token: Token<'_>, what: &str) -> Result<String, Located> {
    if is_name(token.text) {
        Ok(token.text.to_string())
    } else {
        Err((
            token.loc,
            format!(
                "{what} '{}' is not a valid name; use letters, digits, '_' and '-'",
                token.text
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn token(text: &str) -> Token<'_> {
        Token {
            text,
            loc: Loc::START,
        }
    }

    #[test]
    fn positions_round_to_the_nearest_256th() {
        let fx8 = |t| position_fx8(token(t), "x").expect("valid");
        assert_eq!(fx8("32.5"), 32 * 256 + 128);
        assert_eq!(fx8("-32.5"), -(32 * 256 + 128));
        assert_eq!(fx8("1"), 256);
        assert_eq!(fx8("0.001953125"), 1); // exactly half of 1/256 rounds away from zero
        assert_eq!(fx8("0.0019"), 0);
        assert_eq!(fx8("+2.25"), 576);
        for bad in ["", "1.", ".5", "1e3", "inf", "1..2", "--1", "0x10"] {
            assert!(position_fx8(token(bad), "x").is_err(), "{bad:?}");
        }
    }

    #[test]
    fn degrees_become_binary_angles() {
        let angle = |t| angle_degrees(token(t)).expect("valid");
        assert_eq!(angle("0"), 0);
        assert_eq!(angle("90"), 16384);
        assert_eq!(angle("180"), 32768);
        assert_eq!(angle("270"), 49152);
        assert_eq!(angle("360"), 0);
        assert_eq!(angle("-90"), 49152);
        assert_eq!(angle("45.5"), 8283); // 45.5 / 360 * 65536 = 8283.0
        assert_eq!(angle("720.0"), 0);
    }

    #[test]
    fn integers_and_names() {
        assert_eq!(integer(token("-42"), "n"), Ok(-42));
        assert!(integer(token("4.2"), "n").is_err());
        assert!(integer(token("1099511627777"), "n").is_err());
        assert!(integer(token("-9223372036854775808"), "n").is_err());
        assert!(integer_in(token("300"), "light", 0, 255).is_err());
        assert!(is_name("hall_2-b") && !is_name("a.b") && !is_name(""));
    }

    #[test]
    fn tokens_carry_character_columns() {
        let words = tokens("  é vertex\tv1  ", 7);
        let found: Vec<(&str, u32)> = words.iter().map(|w| (w.text, w.loc.col)).collect();
        assert_eq!(found, [("é", 3), ("vertex", 5), ("v1", 12)]);
        assert!(words.iter().all(|w| w.loc.line == 7));
    }
}
