//! The FFI boundary to the C shim (`shim/mgba_shim.c`): the only module with `unsafe`.
//!
//! Everything above this module works with [`RawEmulator`], whose methods are safe because it owns
//! a valid `pc_emu` for its whole life and, not being `Sync`, is never used from two threads at
//! once (see the shim header for the threading contract of the log routing).

#![allow(unsafe_code)]

use std::ffi::{c_char, c_int, CStr, CString};
use std::ptr::NonNull;
use std::sync::{Mutex, MutexGuard};

/// Width of the GBA screen in pixels (`PC_SCREEN_WIDTH` in the shim).
pub const SCREEN_WIDTH: usize = 240;
/// Height of the GBA screen in pixels (`PC_SCREEN_HEIGHT` in the shim).
pub const SCREEN_HEIGHT: usize = 160;

/// Serialises core creation and destruction: that is where libmgba touches process-wide state
/// (file and ELF loading, directory handles), which we would rather not audit for thread safety.
/// Running frames is not serialised: mGBA cores share no mutable state (mGBA itself runs several
/// cores on several threads for link play).
static LIFECYCLE: Mutex<()> = Mutex::new(());

fn lifecycle() -> MutexGuard<'static, ()> {
    // A panic while holding the lock cannot leave the () inside inconsistent.
    LIFECYCLE
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

#[repr(C)]
struct PcEmu {
    _opaque: [u8; 0],
}

extern "C" {
    fn pc_emu_create(
        path: *const c_char,
        as_cartridge: c_int,
        err: *mut c_char,
        err_len: usize,
    ) -> *mut PcEmu;
    fn pc_emu_destroy(emu: *mut PcEmu);
    fn pc_emu_set_keys(emu: *mut PcEmu, keys: u32);
    fn pc_emu_run_frame(emu: *mut PcEmu);
    fn pc_emu_frame(emu: *const PcEmu) -> *const u32;
    fn pc_emu_read8(emu: *mut PcEmu, address: u32) -> u32;
    fn pc_emu_read16(emu: *mut PcEmu, address: u32) -> u32;
    fn pc_emu_read32(emu: *mut PcEmu, address: u32) -> u32;
    fn pc_emu_read_bytes(emu: *mut PcEmu, address: u32, out: *mut u8, len: usize);
    fn pc_emu_write_bytes(emu: *mut PcEmu, address: u32, bytes: *const u8, len: usize);
    fn pc_emu_cycles(emu: *const PcEmu) -> u64;
    fn pc_emu_frame_counter(emu: *mut PcEmu) -> u32;
    fn pc_emu_log_count(emu: *const PcEmu) -> usize;
    fn pc_emu_log_entry(
        emu: *const PcEmu,
        index: usize,
        level: *mut c_int,
        category: *mut *const c_char,
        text: *mut *const c_char,
    ) -> c_int;
    fn pc_emu_log_dropped(emu: *const PcEmu) -> usize;
    fn pc_emu_log_clear(emu: *mut PcEmu);
    fn pc_emu_profile_start(emu: *mut PcEmu, period: u32);
    fn pc_emu_profile_stop(emu: *mut PcEmu);
    fn pc_emu_profile_samples(emu: *const PcEmu, pairs: *mut *const u32) -> usize;
    fn pc_emu_profile_clear(emu: *mut PcEmu);
}

/// One log line as the shim recorded it, before the safe layer gives the level a type.
pub struct RawLogLine {
    pub level: i32,
    pub category: String,
    pub text: String,
}

/// How the shim hands a file to mGBA.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadAs {
    /// Map it as a cartridge image at 0x08000000, as a real GBA would boot it.
    Cartridge,
    /// Let mGBA's loader decide (ELF program headers, multiboot detection).
    MgbaDecides,
}

/// Owns one mGBA core (through the shim). Not `Sync`: the raw pointer makes sure of that.
pub struct RawEmulator {
    emu: NonNull<PcEmu>,
}

// SAFETY: the shim keeps no thread affinity: each call brackets itself with the calling thread's
// "current emulator", so moving the owner to another thread between calls is fine. Concurrent use
// is excluded because RawEmulator is not Sync and every mutating call takes &mut self.
unsafe impl Send for RawEmulator {}

impl RawEmulator {
    /// Creates a core and loads `path` into it; on failure, mGBA's reason as one line.
    pub fn open(path: &CStr, load_as: LoadAs) -> Result<RawEmulator, String> {
        let mut err = vec![0 as c_char; 512];
        let _guard = lifecycle();
        // SAFETY: path is NUL-terminated; err is writable for err.len() bytes and the shim always
        // NUL-terminates what it writes there.
        let as_cartridge = c_int::from(load_as == LoadAs::Cartridge);
        let emu =
            unsafe { pc_emu_create(path.as_ptr(), as_cartridge, err.as_mut_ptr(), err.len()) };
        match NonNull::new(emu) {
            Some(emu) => Ok(RawEmulator { emu }),
            None => {
                // SAFETY: see above: a NUL-terminated string inside `err`.
                let reason = unsafe { CStr::from_ptr(err.as_ptr()) };
                Err(reason.to_string_lossy().into_owned())
            }
        }
    }

    /// Sets the held keys (GBA KEYINPUT bit order, 1 = held).
    pub fn set_keys(&mut self, keys: u32) {
        // SAFETY: self.emu is valid for the life of self.
        unsafe { pc_emu_set_keys(self.emu.as_ptr(), keys) }
    }

    /// Emulates one whole frame (until the next frame boundary).
    pub fn run_frame(&mut self) {
        // SAFETY: self.emu is valid for the life of self.
        unsafe { pc_emu_run_frame(self.emu.as_ptr()) }
    }

    /// The last completed frame, `SCREEN_WIDTH * SCREEN_HEIGHT` packed pixels (red in bits 0-7).
    pub fn frame(&self) -> &[u32] {
        // SAFETY: the shim owns a buffer of exactly this many u32 for the life of the emulator and
        // writes it only during run_frame, which needs &mut self, so the borrow cannot overlap.
        unsafe {
            let pixels = pc_emu_frame(self.emu.as_ptr());
            std::slice::from_raw_parts(pixels, SCREEN_WIDTH * SCREEN_HEIGHT)
        }
    }

    /// Reads a byte as the CPU would see it.
    pub fn read8(&self, address: u32) -> u8 {
        // SAFETY: self.emu is valid; the read does not touch the log buffer (the shim routes the
        // lines of memory probes nowhere), so &self is enough.
        unsafe { pc_emu_read8(self.emu.as_ptr(), address) as u8 }
    }

    /// Reads a halfword as the CPU would see it.
    pub fn read16(&self, address: u32) -> u16 {
        // SAFETY: as read8.
        unsafe { pc_emu_read16(self.emu.as_ptr(), address) as u16 }
    }

    /// Reads a word as the CPU would see it.
    pub fn read32(&self, address: u32) -> u32 {
        // SAFETY: as read8.
        unsafe { pc_emu_read32(self.emu.as_ptr(), address) }
    }

    /// Fills `out` with the bytes starting at `address`.
    pub fn read_bytes(&self, address: u32, out: &mut [u8]) {
        // SAFETY: as read8; `out` is writable for out.len() bytes.
        unsafe { pc_emu_read_bytes(self.emu.as_ptr(), address, out.as_mut_ptr(), out.len()) }
    }

    /// Writes `bytes` from `address` on, as a debugger patches memory.
    pub fn write_bytes(&mut self, address: u32, bytes: &[u8]) {
        // SAFETY: as read8; `bytes` is readable for bytes.len() bytes.
        unsafe { pc_emu_write_bytes(self.emu.as_ptr(), address, bytes.as_ptr(), bytes.len()) }
    }

    /// CPU cycles since reset.
    pub fn cycles(&self) -> u64 {
        // SAFETY: self.emu is valid for the life of self.
        unsafe { pc_emu_cycles(self.emu.as_ptr()) }
    }

    /// Starts (or restarts) sampling `(pc, lr)` every `period` cycles.
    pub fn profile_start(&mut self, period: u32) {
        // SAFETY: self.emu is valid; the shim owns the event it schedules.
        unsafe { pc_emu_profile_start(self.emu.as_ptr(), period) }
    }

    /// Stops sampling; the samples stay.
    pub fn profile_stop(&mut self) {
        // SAFETY: self.emu is valid.
        unsafe { pc_emu_profile_stop(self.emu.as_ptr()) }
    }

    /// Takes the `(pc, lr)` samples recorded so far.
    pub fn profile_take(&mut self) -> Vec<(u32, u32)> {
        let mut pairs: *const u32 = std::ptr::null();
        // SAFETY: self.emu is valid; the shim returns `count` pairs at `pairs`, which stay valid
        // until the next call into this emulator, and we copy them before pc_emu_profile_clear.
        unsafe {
            let count = pc_emu_profile_samples(self.emu.as_ptr(), &mut pairs);
            let samples = if count == 0 {
                Vec::new()
            } else {
                std::slice::from_raw_parts(pairs, 2 * count)
                    .chunks_exact(2)
                    .map(|pair| (pair[0], pair[1]))
                    .collect()
            };
            pc_emu_profile_clear(self.emu.as_ptr());
            samples
        }
    }

    /// mGBA's own frame counter.
    pub fn frame_counter(&self) -> u32 {
        // SAFETY: self.emu is valid; frameCounter only reads.
        unsafe { pc_emu_frame_counter(self.emu.as_ptr()) }
    }

    /// Takes every line the shim recorded since the last call, and how many it had to drop.
    pub fn take_log(&mut self) -> (Vec<RawLogLine>, usize) {
        let ptr = self.emu.as_ptr();
        // SAFETY: self.emu is valid; the entries' strings stay valid until pc_emu_log_clear, which
        // is called only after they have all been copied.
        unsafe {
            let count = pc_emu_log_count(ptr);
            let mut lines = Vec::with_capacity(count);
            for index in 0..count {
                let mut level: c_int = 0;
                let mut category: *const c_char = std::ptr::null();
                let mut text: *const c_char = std::ptr::null();
                if pc_emu_log_entry(ptr, index, &mut level, &mut category, &mut text) == 0 {
                    break;
                }
                lines.push(RawLogLine {
                    level,
                    category: lossy(category),
                    text: lossy(text),
                });
            }
            let dropped = pc_emu_log_dropped(ptr);
            pc_emu_log_clear(ptr);
            (lines, dropped)
        }
    }
}

impl Drop for RawEmulator {
    fn drop(&mut self) {
        let _guard = lifecycle();
        // SAFETY: self.emu came from pc_emu_create and is destroyed exactly once, here.
        unsafe { pc_emu_destroy(self.emu.as_ptr()) }
    }
}

/// Copies a C string the shim handed out; NULL becomes "".
///
/// # Safety
/// `ptr` is NULL or a valid NUL-terminated string.
unsafe fn lossy(ptr: *const c_char) -> String {
    if ptr.is_null() {
        String::new()
    } else {
        // SAFETY: the caller guarantees a valid NUL-terminated string.
        unsafe { CStr::from_ptr(ptr) }
            .to_string_lossy()
            .into_owned()
    }
}

/// Converts a path to the C string the shim wants; `None` if it contains a NUL byte.
pub fn path_to_cstring(path: &std::path::Path) -> Option<CString> {
    use std::os::unix::ffi::OsStrExt;
    CString::new(path.as_os_str().as_bytes()).ok()
}
