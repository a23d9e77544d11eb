/* A thin C layer over Debian's libmgba 0.10 for the portalcast harness.
 *
 * Why a C layer at all: `struct mCore` is a table of function pointers whose layout depends on the
 * build flags of the installed library (<mgba/flags.h>), so binding it from Rust by hand would be
 * fragile. The C compiler sees the real headers; Rust only sees the small opaque API below.
 *
 * Threading contract: a `pc_emu` may be used from any thread, but from one thread at a time.
 * mGBA's logger is process-global, so the shim installs ONE logger and routes each line to the
 * emulator that is running on the calling thread (a thread-local "current emulator" set by every
 * entry point below for the duration of the call). Two emulators on two threads never see each
 * other's lines.
 */
#ifndef PORTALCAST_MGBA_SHIM_H
#define PORTALCAST_MGBA_SHIM_H

#include <stddef.h>
#include <stdint.h>

#define PC_SCREEN_WIDTH 240
#define PC_SCREEN_HEIGHT 160

typedef struct pc_emu pc_emu;

/* Creates a GBA core, loads the ROM or ELF at `path` and resets it (HLE BIOS, no BIOS file).
 * `as_cartridge` != 0 maps the file as a cartridge image, whatever it contains; 0 lets mGBA
 * decide (ELF loader, multiboot detection).
 * Returns NULL on failure and writes a one-line reason into `err` (always NUL-terminated). */
pc_emu* pc_emu_create(const char* path, int as_cartridge, char* err, size_t err_len);
void pc_emu_destroy(pc_emu* emu);

/* GBA key bits: A=0 B=1 Select=2 Start=3 Right=4 Left=5 Up=6 Down=7 R=8 L=9. A set bit = held. */
void pc_emu_set_keys(pc_emu* emu, uint32_t keys);
void pc_emu_run_frame(pc_emu* emu);

/* The last completed frame: PC_SCREEN_WIDTH * PC_SCREEN_HEIGHT 32-bit pixels, row-major, no
 * padding. Each pixel is mGBA's 32-bit color_t: red in bits 0-7, green 8-15, blue 16-23. */
const uint32_t* pc_emu_frame(const pc_emu* emu);

uint32_t pc_emu_read8(pc_emu* emu, uint32_t address);
uint32_t pc_emu_read16(pc_emu* emu, uint32_t address);
uint32_t pc_emu_read32(pc_emu* emu, uint32_t address);
void pc_emu_read_bytes(pc_emu* emu, uint32_t address, uint8_t* out, size_t len);
/* Writes `len` bytes from `address` on, as a debugger patches memory (no timing, no I/O side
 * effects; a VRAM byte is one byte). */
void pc_emu_write_bytes(pc_emu* emu, uint32_t address, const uint8_t* bytes, size_t len);

/* CPU cycles since reset (16.78 MHz clock) and mGBA's own frame counter. */
uint64_t pc_emu_cycles(const pc_emu* emu);
uint32_t pc_emu_frame_counter(pc_emu* emu);

/* Sampling profiler: every `period` CPU cycles, record the (pc, lr) pair the CPU is at; pc has
 * bit 0 set in Thumb state. Samples accumulate until pc_emu_profile_clear; `pairs` points at
 * 2 * count words, valid until the next call into this emulator. */
void pc_emu_profile_start(pc_emu* emu, uint32_t period);
void pc_emu_profile_stop(pc_emu* emu);
size_t pc_emu_profile_samples(const pc_emu* emu, const uint32_t** pairs);
void pc_emu_profile_clear(pc_emu* emu);

/* Log lines recorded since the last pc_emu_log_clear. `category` and `text` stay valid until then.
 * Returns 0 if `index` is out of range. */
size_t pc_emu_log_count(const pc_emu* emu);
int pc_emu_log_entry(const pc_emu* emu, size_t index, int* level, const char** category,
                     const char** text);
/* Lines thrown away because the buffer was full (see PC_LOG_CAPACITY in the .c). */
size_t pc_emu_log_dropped(const pc_emu* emu);
void pc_emu_log_clear(pc_emu* emu);

#endif
