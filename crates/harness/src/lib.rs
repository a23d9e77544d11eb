//! Drives the real mGBA core (Debian's libmgba 0.10) headless: keys in; frames, log lines, memory
//! and cycle counts out.
//!
//! ```no_run
//! use portalcast_harness::{Emulator, KeyScript};
//! use std::path::Path;
//!
//! let mut emu = Emulator::load(Path::new("target/portalcast.gba"))?;
//! let script: KeyScript = "0-59: UP\n60: A\n".parse()?;
//! emu.run_script(&script, 120)?; // Err if the ROM panicked or mGBA logged a fatal line
//! println!("{:?}", emu.debug_lines());
//! emu.save_frame_png(Path::new("target/frames/last.png"))?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Threads and logging
//!
//! mGBA has one process-wide logger. The C shim installs it once and routes every line to the
//! emulator whose call is running on the current thread (a thread-local set around each call), so
//! emulators on different threads — `cargo test` runs tests in parallel — each get exactly their
//! own lines, while running truly in parallel. Only creating and dropping an emulator is
//! serialised (a global mutex): that is where libmgba touches process-wide state (file and ELF
//! loading), and it costs nothing next to emulation.
//!
//! [`Emulator`] is `Send` but not `Sync`: move it to another thread freely, share it never.

#![warn(missing_docs)]
// `unsafe` lives in `ffi` only, which opts back in.
#![deny(unsafe_code)]

mod ffi;
mod keys;
pub mod symbols;

use std::fmt;
use std::path::{Path, PathBuf};

pub use ffi::{SCREEN_HEIGHT, SCREEN_WIDTH};
pub use keys::{KeyScript, KeyScriptError, Keys};

/// What to tell someone whose ROM file is missing or unusable.
const BUILD_HINT: &str = "build it with `cargo rom`";

/// The mGBA log category of the ROM's debug prints (registers at 0x04FFF600..0x04FFF780).
pub const GBA_DEBUG_CATEGORY: &str = "GBA Debug";

/// The largest cartridge image the GBA maps (0x08000000..0x0A000000).
const MAX_ROM_BYTES: u64 = 32 << 20;

/// The log keeps at most this many lines; older ones are dropped (and counted) beyond it, so a
/// long run of a chatty ROM cannot exhaust memory.
const MAX_RETAINED_LOG_LINES: usize = 100_000;

/// Everything that can go wrong while loading or running a ROM.
#[derive(Debug)]
#[non_exhaustive]
pub enum HarnessError {
    /// The ROM path does not exist.
    RomNotFound {
        /// The path that was asked for.
        path: PathBuf,
    },
    /// The ROM file is empty.
    RomEmpty {
        /// The empty file.
        path: PathBuf,
    },
    /// The file is neither a GBA cartridge image nor an ARM ELF for the GBA.
    NotARom {
        /// The rejected file.
        path: PathBuf,
        /// Which check failed.
        reason: String,
    },
    /// The file passed the harness's checks but mGBA refused it.
    MgbaRejected {
        /// The rejected file.
        path: PathBuf,
        /// mGBA's reason, as far as it tells.
        reason: String,
    },
    /// The ROM printed a line starting with `panic` on the mGBA debug output.
    RomPanicked {
        /// The frame (counted from 1 since load) during which it happened.
        frame: u64,
        /// The panic line without its leading `panic:`, plus its continuation lines (the debug
        /// prints right after it at the same level), joined with newlines.
        message: String,
    },
    /// mGBA logged a line at level Fatal (the ROM's own fatal debug prints included).
    RomFatal {
        /// The frame (counted from 1 since load) during which it happened.
        frame: u64,
        /// The mGBA log category of the line.
        category: String,
        /// The line.
        message: String,
    },
    /// A key script file has a syntax error.
    KeyScript {
        /// The script file.
        path: PathBuf,
        /// Where and what.
        source: KeyScriptError,
    },
    /// Reading or writing a file failed.
    Io {
        /// The file.
        path: PathBuf,
        /// What the harness was doing, e.g. "read the ROM".
        action: &'static str,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// Encoding or writing a PNG failed.
    Png {
        /// The PNG file.
        path: PathBuf,
        /// The encoder's error.
        source: image::ImageError,
    },
}

impl fmt::Display for HarnessError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HarnessError::RomNotFound { path } => {
                write!(f, "ROM {} does not exist: {BUILD_HINT}", path.display())
            }
            HarnessError::RomEmpty { path } => {
                write!(f, "ROM {} is an empty file: {BUILD_HINT}", path.display())
            }
            HarnessError::NotARom { path, reason } => write!(
                f,
                "{} is not a GBA ROM: {reason}; {BUILD_HINT}",
                path.display()
            ),
            HarnessError::MgbaRejected { path, reason } => write!(
                f,
                "mGBA cannot run {}: {reason}; rebuild it with `cargo rom`",
                path.display()
            ),
            HarnessError::RomPanicked { frame, message } => {
                write!(f, "the ROM panicked during frame {frame}: {message}")
            }
            HarnessError::RomFatal {
                frame,
                category,
                message,
            } => write!(
                f,
                "mGBA logged a fatal error during frame {frame} [{category}]: {message}"
            ),
            HarnessError::KeyScript { path, source } => {
                write!(f, "{}: {source}", path.display())
            }
            HarnessError::Io {
                path,
                action,
                source,
            } => write!(f, "cannot {action} {}: {source}", path.display()),
            HarnessError::Png { path, source } => {
                write!(f, "cannot write PNG {}: {source}", path.display())
            }
        }
    }
}

impl std::error::Error for HarnessError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            HarnessError::KeyScript { source, .. } => Some(source),
            HarnessError::Io { source, .. } => Some(source),
            HarnessError::Png { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// Severity of a log line, as mGBA grades it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LogLevel {
    /// Unrecoverable; also the ROM's debug prints at level 0.
    Fatal,
    /// An error.
    Error,
    /// A warning.
    Warn,
    /// Information.
    Info,
    /// Debugging detail.
    Debug,
    /// The game used something mGBA does not emulate.
    Stub,
    /// The game did something a real GBA would not like (e.g. a bad memory access).
    GameError,
    /// A level this harness does not know (raw mGBA value).
    Other(i32),
}

impl LogLevel {
    fn from_mgba(level: i32) -> LogLevel {
        // The mLOG_* values of <mgba/core/log.h>.
        match level {
            0x01 => LogLevel::Fatal,
            0x02 => LogLevel::Error,
            0x04 => LogLevel::Warn,
            0x08 => LogLevel::Info,
            0x10 => LogLevel::Debug,
            0x20 => LogLevel::Stub,
            0x40 => LogLevel::GameError,
            other => LogLevel::Other(other),
        }
    }
}

impl fmt::Display for LogLevel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LogLevel::Fatal => f.write_str("fatal"),
            LogLevel::Error => f.write_str("error"),
            LogLevel::Warn => f.write_str("warn"),
            LogLevel::Info => f.write_str("info"),
            LogLevel::Debug => f.write_str("debug"),
            LogLevel::Stub => f.write_str("stub"),
            LogLevel::GameError => f.write_str("game error"),
            LogLevel::Other(level) => write!(f, "level {level:#x}"),
        }
    }
}

/// One line of mGBA's log.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LogLine {
    /// mGBA's category name, e.g. `GBA Debug` (the ROM's prints), `GBA BIOS`, `GBA Memory`.
    pub category: String,
    /// Severity.
    pub level: LogLevel,
    /// The formatted message.
    pub text: String,
}

impl LogLine {
    /// True for the ROM's own debug prints.
    pub fn is_debug_print(&self) -> bool {
        self.category == GBA_DEBUG_CATEGORY
    }
}

/// Writes `[category] level: text`.
impl fmt::Display for LogLine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{}] {}: {}", self.category, self.level, self.text)
    }
}

/// One running GBA: mGBA's core with a ROM loaded, its HLE BIOS, no audio output.
pub struct Emulator {
    raw: ffi::RawEmulator,
    path: PathBuf,
    keys: Keys,
    frames_run: u64,
    log: Vec<LogLine>,
    dropped_log_lines: u64,
}

impl fmt::Debug for Emulator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Emulator")
            .field("path", &self.path)
            .field("keys", &self.keys)
            .field("frames_run", &self.frames_run)
            .field("log_lines", &self.log.len())
            .finish_non_exhaustive()
    }
}

impl Emulator {
    /// Loads a GBA ROM (`.gba` cartridge image) or an ARM ELF linked for the GBA, and resets the
    /// machine. No BIOS file is needed: mGBA's built-in (HLE) BIOS starts the cartridge directly.
    ///
    /// The file is checked before mGBA sees it, so that a missing, empty or wrong file gives an
    /// error that says so (and how to build the ROM) rather than a crash; mGBA's own refusal is
    /// reported as [`HarnessError::MgbaRejected`].
    pub fn load(path: &Path) -> Result<Emulator, HarnessError> {
        let load_as = check_rom_file(path)?;
        let c_path = ffi::path_to_cstring(path).ok_or_else(|| HarnessError::NotARom {
            path: path.to_owned(),
            reason: "the path contains a NUL byte".to_owned(),
        })?;
        let raw = ffi::RawEmulator::open(&c_path, load_as).map_err(|reason| {
            HarnessError::MgbaRejected {
                path: path.to_owned(),
                reason,
            }
        })?;
        let mut emulator = Emulator {
            raw,
            path: path.to_owned(),
            keys: Keys::NONE,
            frames_run: 0,
            log: Vec::new(),
            dropped_log_lines: 0,
        };
        // Lines from loading and reset (mGBA's own chatter) belong in the log too.
        emulator.collect_log();
        Ok(emulator)
    }

    /// The file this emulator was loaded from.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Holds exactly `keys` from the next frame on, until changed.
    pub fn set_keys(&mut self, keys: Keys) {
        self.keys = keys;
        self.raw.set_keys(u32::from(keys.bits()));
    }

    /// The keys currently held.
    pub fn keys(&self) -> Keys {
        self.keys
    }

    /// Emulates up to the next frame boundary (the start of VBlank, so the picture is complete):
    /// 280 896 CPU cycles, fewer for the first frame after load (see [`Emulator::frame_rgb`]).
    /// Then collects the log lines the frame produced.
    ///
    /// Fails with [`HarnessError::RomPanicked`] if the ROM printed a line starting with `panic`
    /// on the mGBA debug output during the frame, or [`HarnessError::RomFatal`] if any line at
    /// level Fatal appeared. The frame has still run and its lines are in the log; the emulator
    /// can keep going if the caller wishes (mGBA itself does not stop on a fatal line).
    pub fn run_frame(&mut self) -> Result<(), HarnessError> {
        self.raw.run_frame();
        self.frames_run += 1;
        let first_new = self.collect_log();
        self.check_new_lines(first_new)
    }

    /// Runs `frames` frames with the current keys, stopping at the first failing frame (see
    /// [`Emulator::run_frame`]).
    pub fn run_frames(&mut self, frames: u32) -> Result<(), HarnessError> {
        for _ in 0..frames {
            self.run_frame()?;
        }
        Ok(())
    }

    /// Runs `frames` frames, holding on frame `i` (0 = the first one run here) the keys
    /// `script.keys_at(i)`; stops at the first failing frame (see [`Emulator::run_frame`]).
    ///
    /// All keys are released afterwards, also on failure: a script describes the input of its
    /// own frames only.
    pub fn run_script(&mut self, script: &KeyScript, frames: u32) -> Result<(), HarnessError> {
        let mut result = Ok(());
        for frame in 0..frames {
            self.set_keys(script.keys_at(frame));
            result = self.run_frame();
            if result.is_err() {
                break;
            }
        }
        self.set_keys(Keys::NONE);
        result
    }

    /// Frames run since load.
    pub fn frames_run(&self) -> u64 {
        self.frames_run
    }

    /// CPU cycles emulated since reset (the CPU runs at 2^24 Hz; a frame is 280 896 cycles).
    pub fn cycles(&self) -> u64 {
        self.raw.cycles()
    }

    /// Starts a cycle-weighted sampling profile: every `period` CPU cycles the emulator records
    /// the instruction address it is at and the link register. A prime period avoids beating
    /// with the ROM's own loops.
    pub fn profile_start(&mut self, period: u32) {
        self.raw.profile_start(period);
    }

    /// Stops the profile; the samples stay until [`Emulator::profile_take`].
    pub fn profile_stop(&mut self) {
        self.raw.profile_stop();
    }

    /// Takes the samples recorded since the last call: `(pc, lr)`, with bit 0 of `pc` set when
    /// the CPU was in Thumb state.
    pub fn profile_take(&mut self) -> Vec<(u32, u32)> {
        self.raw.profile_take()
    }

    /// mGBA's own count of frames drawn since reset.
    pub fn mgba_frame_counter(&self) -> u32 {
        self.raw.frame_counter()
    }

    /// The last completed frame as a 240x160 RGB image.
    ///
    /// The first frame after load is partial: mGBA's BIOS skip starts the machine at scanline
    /// 126, so only lines 126-159 are drawn and the rest is white. Look from the second frame on.
    ///
    /// The GBA's 5-bit channels are widened the way mGBA does it (`c << 3 | c >> 2`), so pure
    /// red `0x001F` becomes (255, 0, 0).
    pub fn frame_rgb(&self) -> image::RgbImage {
        let pixels = self.raw.frame();
        let mut bytes = Vec::with_capacity(pixels.len() * 3);
        for &pixel in pixels {
            // mGBA's 32-bit color_t is XBGR8: red in the lowest byte.
            bytes.extend_from_slice(&[pixel as u8, (pixel >> 8) as u8, (pixel >> 16) as u8]);
        }
        image::RgbImage::from_raw(SCREEN_WIDTH as u32, SCREEN_HEIGHT as u32, bytes)
            .expect("the shim's frame buffer is exactly 240x160 pixels")
    }

    /// Writes the last completed frame to `path` as a PNG (the directory must exist).
    pub fn save_frame_png(&self, path: &Path) -> Result<(), HarnessError> {
        self.frame_rgb()
            .save_with_format(path, image::ImageFormat::Png)
            .map_err(|source| HarnessError::Png {
                path: path.to_owned(),
                source,
            })
    }

    /// Every log line since load (or the last [`Emulator::drain_log`]), oldest first, all
    /// categories and levels. Filter with [`LogLine::is_debug_print`] or by `level`.
    pub fn log_lines(&self) -> &[LogLine] {
        &self.log
    }

    /// Takes the log lines collected so far, leaving the log empty.
    pub fn drain_log(&mut self) -> Vec<LogLine> {
        std::mem::take(&mut self.log)
    }

    /// The text of the ROM's debug prints (category `GBA Debug`) in the log, oldest first.
    pub fn debug_lines(&self) -> Vec<&str> {
        self.log
            .iter()
            .filter(|line| line.is_debug_print())
            .map(|line| line.text.as_str())
            .collect()
    }

    /// Log lines lost so far because a ROM logged too much (more than 100 000 lines retained,
    /// or in a single frame).
    pub fn dropped_log_lines(&self) -> u64 {
        self.dropped_log_lines
    }

    /// Reads the byte at `address` as the CPU would see it (any GBA address: EWRAM 0x02..,
    /// IWRAM 0x03.., I/O 0x04.., palette 0x05.., VRAM 0x06.., OAM 0x07.., ROM 0x08..).
    /// Reading has no effect on the emulation.
    pub fn read_u8(&self, address: u32) -> u8 {
        self.raw.read8(address)
    }

    /// Reads the little-endian halfword at `address` (see [`Emulator::read_u8`]); `address`
    /// should be 2-aligned, as on the CPU.
    pub fn read_u16(&self, address: u32) -> u16 {
        self.raw.read16(address)
    }

    /// Reads the little-endian word at `address` (see [`Emulator::read_u8`]); `address` should
    /// be 4-aligned, as on the CPU.
    pub fn read_u32(&self, address: u32) -> u32 {
        self.raw.read32(address)
    }

    /// Reads `len` bytes starting at `address` (see [`Emulator::read_u8`]).
    pub fn read_bytes(&self, address: u32, len: usize) -> Vec<u8> {
        let mut bytes = vec![0; len];
        self.raw.read_bytes(address, &mut bytes);
        bytes
    }

    /// Writes `bytes` from `address` on, as a debugger patches memory: no timing, no I/O side
    /// effects, and in VRAM exactly the bytes given (the CPU's byte stores would mirror); RAM,
    /// palette, VRAM and OAM all take it, best in word-aligned runs. For
    /// setting up memory before the ROM runs, e.g. the arbitrary RAM contents of a real cold
    /// boot, which mGBA otherwise zeroes.
    pub fn write_bytes(&mut self, address: u32, bytes: &[u8]) {
        self.raw.write_bytes(address, bytes);
    }

    /// Moves the shim's new lines into `self.log`; returns the index of the first new one.
    fn collect_log(&mut self) -> usize {
        let (lines, dropped) = self.raw.take_log();
        self.dropped_log_lines += dropped as u64;
        if self.log.len() + lines.len() > MAX_RETAINED_LOG_LINES {
            // Drop the oldest; the new lines must stay, failure detection reads them.
            let excess =
                (self.log.len() + lines.len() - MAX_RETAINED_LOG_LINES).min(self.log.len());
            self.log.drain(..excess);
            self.dropped_log_lines += excess as u64;
        }
        let first_new = self.log.len();
        self.log.extend(lines.into_iter().map(|raw| LogLine {
            category: raw.category,
            level: LogLevel::from_mgba(raw.level),
            text: raw.text,
        }));
        first_new
    }

    /// The failure, if any, among the log lines from `first_new` on. A panic print wins over a
    /// bare fatal line, since a ROM may well print its panic at level Fatal.
    fn check_new_lines(&self, first_new: usize) -> Result<(), HarnessError> {
        let new = &self.log[first_new..];
        let is_panic = |line: &LogLine| line.is_debug_print() && line.text.starts_with("panic");
        if let Some(start) = new.iter().position(is_panic) {
            return Err(HarnessError::RomPanicked {
                frame: self.frames_run,
                message: panic_message(&new[start..]),
            });
        }
        if let Some(line) = new.iter().find(|line| line.level == LogLevel::Fatal) {
            return Err(HarnessError::RomFatal {
                frame: self.frames_run,
                category: line.category.clone(),
                message: line.text.clone(),
            });
        }
        Ok(())
    }
}

/// The message of the panic print `lines[0]`, without its `panic:` prefix.
///
/// mGBA's debug output carries one line per print, so a ROM logger that sends on every `\n` (as
/// gba's `MgbaBufferedLogger` does) splits a multi-line panic, e.g. core's `panicked at
/// src/x.rs:1:2:` followed by a newline and the message, into several prints. The debug prints
/// right after it at the same level are taken as its continuation and joined back with newlines.
fn panic_message(lines: &[LogLine]) -> String {
    let first = &lines[0];
    let mut message = first.text["panic".len()..]
        .trim_start_matches(':')
        .trim()
        .to_owned();
    for line in lines[1..]
        .iter()
        .filter(|line| line.is_debug_print())
        .take_while(|line| line.level == first.level && !line.text.starts_with("panic"))
    {
        message.push('\n');
        message.push_str(&line.text);
    }
    message
}

/// Checks that `path` plausibly holds a GBA ROM or a GBA ELF, mirroring what mGBA accepts, and
/// says how to load it.
///
/// A cartridge image is always mapped as a cartridge: mGBA's own loader would take a small image
/// (256 KiB or less) for a multiboot program when its first instructions look like one, and run
/// it from EWRAM with an empty cartridge. Only a `.mb` file gets mGBA's multiboot detection.
fn check_rom_file(path: &Path) -> Result<ffi::LoadAs, HarnessError> {
    let metadata = match std::fs::metadata(path) {
        Ok(metadata) => metadata,
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => {
            return Err(HarnessError::RomNotFound {
                path: path.to_owned(),
            })
        }
        Err(source) => {
            return Err(HarnessError::Io {
                path: path.to_owned(),
                action: "read the ROM",
                source,
            })
        }
    };
    let not_a_rom = |reason: String| HarnessError::NotARom {
        path: path.to_owned(),
        reason,
    };
    if !metadata.is_file() {
        return Err(not_a_rom("it is a directory, not a file".to_owned()));
    }
    if metadata.len() == 0 {
        return Err(HarnessError::RomEmpty {
            path: path.to_owned(),
        });
    }
    let header = read_prefix(path, 0xC0)?;
    if header.starts_with(b"\x7fELF") {
        check_elf_header(&header).map_err(not_a_rom)?;
        return Ok(ffi::LoadAs::MgbaDecides);
    }
    if metadata.len() > MAX_ROM_BYTES {
        return Err(not_a_rom(format!(
            "it has {} bytes, more than the 32 MiB a cartridge can map",
            metadata.len()
        )));
    }
    check_cartridge_header(&header).map_err(not_a_rom)?;
    let multiboot = path.extension().is_some_and(|extension| extension == "mb");
    Ok(if multiboot {
        ffi::LoadAs::MgbaDecides
    } else {
        ffi::LoadAs::Cartridge
    })
}

/// The first `len` bytes of the file (fewer if it is shorter).
fn read_prefix(path: &Path, len: u64) -> Result<Vec<u8>, HarnessError> {
    use std::io::Read;
    let io_error = |source| HarnessError::Io {
        path: path.to_owned(),
        action: "read the ROM",
        source,
    };
    let file = std::fs::File::open(path).map_err(io_error)?;
    let mut prefix = Vec::new();
    file.take(len).read_to_end(&mut prefix).map_err(io_error)?;
    Ok(prefix)
}

/// The checks of mGBA's `GBAIsROM` for a cartridge image, with reasons a person can act on.
fn check_cartridge_header(header: &[u8]) -> Result<(), String> {
    if header.len() < 0xC0 {
        return Err(format!(
            "it has {} bytes, fewer than the 192-byte cartridge header",
            header.len()
        ));
    }
    // The entry point is an ARM `B` instruction, whose top byte is 0xEA (cond AL, opcode B).
    if header[3] != 0xEA {
        return Err(format!(
            "it does not start with a branch instruction (byte 3 is {:#04x}, not 0xea)",
            header[3]
        ));
    }
    // mGBA takes either the fixed value 0x96 at 0xB2, or an all-zero logo (an unfixed ROM,
    // e.g. the raw output of a linker before a gbafix step).
    let logo_is_blank = header[0x04..0xA0].iter().all(|&byte| byte == 0);
    if header[0xB2] != 0x96 && !logo_is_blank {
        return Err(format!(
            "header byte 0xb2 is {:#04x}, not the fixed 0x96 (was gbafix run?)",
            header[0xB2]
        ));
    }
    Ok(())
}

/// The checks of mGBA's `GBAIsROM` for an ELF, with reasons a person can act on.
fn check_elf_header(header: &[u8]) -> Result<(), String> {
    const ELF32_HEADER_BYTES: usize = 52;
    const EM_ARM: u16 = 40;
    if header.len() < ELF32_HEADER_BYTES {
        return Err("the ELF header is truncated".to_owned());
    }
    if header[4] != 1 || header[5] != 1 {
        return Err("the ELF file is not 32-bit little-endian".to_owned());
    }
    let machine = u16::from_le_bytes([header[0x12], header[0x13]]);
    if machine != EM_ARM {
        return Err(format!(
            "the ELF file is for machine {machine}, not ARM ({EM_ARM})"
        ));
    }
    let entry = u32::from_le_bytes([header[0x18], header[0x19], header[0x1A], header[0x1B]]);
    // mGBA boots an ELF only from the start of the cartridge or (multiboot) of EWRAM.
    if entry != 0x0800_0000 && entry != 0x0200_0000 {
        return Err(format!(
            "its entry point is {entry:#010x}, but mGBA boots an ELF only at 0x08000000 \
             (cartridge) or 0x02000000 (multiboot)"
        ));
    }
    Ok(())
}
