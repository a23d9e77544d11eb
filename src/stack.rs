//! Where the GBA's user stack lives and how its depth is measured: shared by the ROM, which
//! paints the stack's room at boot (`hw::memory::paint_stack`), and the host tests, which read
//! the paint back out of the emulator's IWRAM.

/// Start of IWRAM.
pub const IWRAM_START: usize = 0x0300_0000;

/// Where the BIOS's user-mode stack starts; it grows down towards the ROM's data. The 256 bytes
/// above belong to the BIOS.
pub const STACK_TOP: usize = 0x0300_7F00;

/// The word the boot code paints the stack's room with; the deepest word that no longer holds it
/// marks how far the stack has ever reached. An odd, unlikely value: not a small integer, not an
/// address in any GBA region, not a pattern of repeated bytes.
pub const STACK_PAINT: u32 = 0x5AC3_3CA5;
