//! Lines to mGBA's debug log (category "GBA Debug"); silently dropped on hardware without it.

use core::fmt::{Arguments, Write};
use gba::mgba::{MgbaBufferedLogger, MgbaMessageLevel};

fn print_at(level: MgbaMessageLevel, args: Arguments) {
    if let Ok(mut logger) = MgbaBufferedLogger::try_new(level) {
        // The logger cannot fail: it flushes every 256 bytes and on drop.
        let _ = logger.write_fmt(args);
    }
}

/// Prints one Info-level line.
pub fn info(args: Arguments) {
    print_at(MgbaMessageLevel::Info, args);
}

/// Prints one Fatal-level line. mGBA's frontends stop on it (the bare core used by the harness
/// does not; the harness fails the run instead), so this is the last thing the ROM prints.
pub fn fatal(args: Arguments) {
    print_at(MgbaMessageLevel::Fatal, args);
}
