//! Buttons sampled at every VBlank, in the VBlank interrupt, into a ring the game drains once
//! per drawn frame: the game runs one tick per sample, so it advances at 60 ticks per second
//! whatever the frame rate, and never misses a press shorter than a frame.
//!
//! The engine owns gba's interrupt handler; a game's own handler runs after it, on every
//! interrupt, through [`chain`].

use gba::interrupts::{IrqBits, IrqFn};
use gba::prelude::GbaCell;
use gba::RUST_IRQ_HANDLER;

/// Samples the ring holds: a frame may take up to this many VBlanks before the oldest samples
/// are overwritten (and their ticks skipped). The slowest setting takes about 12.
pub const RING_SAMPLES: u32 = 64;

// In EWRAM (copied in at boot with its zeros): the VBlank handler writes a sample a frame and
// the game reads a few, and IWRAM's bytes go to the renderer's hot code.
#[link_section = ".ewram"]
static RING: [GbaCell<u16>; RING_SAMPLES as usize] = [const { GbaCell::new(0) }; 64];
/// Samples written since [`start`]; the next goes to `RING[WRITTEN % RING_SAMPLES]`.
static WRITTEN: GbaCell<u32> = GbaCell::new(0);

/// The game's handler, called after the sampler's on every interrupt.
/// Held as gba's `IrqFn` (an `unsafe` function pointer, the type its cell takes), but only ever
/// set from a safe function ([`chain`]).
static CHAINED: GbaCell<Option<IrqFn>> = GbaCell::new(None);

/// Runs in IRQ mode on every interrupt (the display enables VBlank's; a game may enable more).
/// In IWRAM: it interrupts every frame once or more, and from the cartridge its ARM code cost
/// the frame more than its 116 bytes of IWRAM are worth elsewhere (docs/BENCH.md).
#[cfg_attr(target_os = "none", link_section = ".iwram.input_on_interrupt")]
extern "C" fn on_interrupt(bits: IrqBits) {
    if bits.vblank() {
        let written = WRITTEN.read();
        RING[(written % RING_SAMPLES) as usize].write(super::keys_held());
        WRITTEN.write(written.wrapping_add(1));
    }
    if let Some(chained) = CHAINED.read() {
        // SAFETY: `chain` stores only safe functions.
        unsafe { chained(bits) };
    }
}

/// Has `handler` run on every interrupt after the engine's own (the button sampler), with the
/// bits of the interrupts being served; `None` removes it. It runs in IRQ mode on the BIOS's
/// small IRQ stack, with interrupts masked: keep it short. The VBlank interrupt stays enabled
/// (the display and the sampler need it); a game that wants others (a timer, HBlank) enables
/// them in IE and their sources itself, and its handler sees their bits.
pub fn chain(handler: Option<extern "C" fn(IrqBits)>) {
    CHAINED.write(handler.map(|handler| handler as IrqFn));
}

/// Installs the sampler. The VBlank interrupt itself is armed by `video::Display::start`.
pub fn start() {
    RUST_IRQ_HANDLER.write(Some(on_interrupt));
}

/// VBlanks sampled since [`start`].
pub fn samples_written() -> u32 {
    WRITTEN.read()
}

/// Reads the samples in order; each reader keeps its own position.
pub struct Sampler {
    read: u32,
}

impl Sampler {
    /// A reader that starts with the next VBlank's sample.
    pub fn new() -> Sampler {
        Sampler {
            read: samples_written(),
        }
    }

    /// Index (VBlanks since [`start`]) of the next sample [`Sampler::drain`] hands out.
    pub fn next_index(&self) -> u32 {
        self.read
    }

    /// Calls `each` with the index (VBlanks since [`start`]) and the buttons of every VBlank
    /// since the last drain, oldest first; if more than [`RING_SAMPLES`] came, only the newest.
    /// Returns how many were lost that way.
    pub fn drain(&mut self, mut each: impl FnMut(u32, u16)) -> u32 {
        let written = samples_written();
        let waiting = written.wrapping_sub(self.read);
        let lost = waiting.saturating_sub(RING_SAMPLES);
        let mut index = self.read.wrapping_add(lost);
        while index != written {
            each(index, RING[(index % RING_SAMPLES) as usize].read());
            index = index.wrapping_add(1);
        }
        self.read = written;
        lost
    }
}

impl Default for Sampler {
    fn default() -> Self {
        Sampler::new()
    }
}
