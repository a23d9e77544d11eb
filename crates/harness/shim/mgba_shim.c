/* See mgba_shim.h for the contract. */

/* Must come first: the mGBA headers do not include it themselves, yet `struct mCore` changes shape
 * with USE_DEBUGGERS / MINIMAL_CORE. Without it we would call through the wrong slots. */
#include <mgba/flags.h>

#include <mgba/core/core.h>
#include <mgba/core/log.h>
#include <mgba/core/timing.h>
#include <mgba/internal/gba/gba.h>
#include <mgba/internal/gba/renderers/video-software.h>
#include <mgba-util/vfs.h>

#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mgba_shim.h"

/* Bounds memory when a ROM floods the log inside one frame (e.g. a print in a tight loop, or a
 * crashed CPU bouncing between an invalid address and the undefined-instruction vector); the Rust
 * side drains after every frame, so this is a per-frame budget. A few fatal lines and panic prints
 * are still kept past it, because failure detection depends on them. */
#define PC_LOG_CAPACITY 100000
#define PC_LOG_FAILURE_RESERVE 16

struct pc_log_entry {
	int level;
	const char* category; /* static string owned by libmgba */
	char* text;           /* malloc'd */
};

struct pc_emu {
	struct mCore* core;
	color_t* video;
	struct pc_log_entry* log;
	size_t log_len;
	size_t log_cap;
	size_t log_dropped;
	/* The sampling profiler (pc_emu_profile_start): a timing event every `profile_period` cycles
	 * records the PC and LR it interrupts. */
	struct mTimingEvent profile_event;
	uint32_t profile_period;
	uint32_t* profile_samples; /* (pc, lr) pairs */
	size_t profile_len;        /* pairs */
	size_t profile_cap;
};

/* The emulator whose call is running on this thread; the global logger routes lines to it. */
static _Thread_local pc_emu* pc_current;

static void pc_log_push(pc_emu* emu, int level, const char* category, char* text) {
	int is_panic = category && strcmp(category, "GBA Debug") == 0 && strncmp(text, "panic", 5) == 0;
	int is_failure = level == mLOG_FATAL || is_panic;
	if (emu->log_len >= PC_LOG_CAPACITY + (is_failure ? PC_LOG_FAILURE_RESERVE : 0)) {
		++emu->log_dropped;
		free(text);
		return;
	}
	if (emu->log_len == emu->log_cap) {
		size_t cap = emu->log_cap ? emu->log_cap * 2 : 64;
		struct pc_log_entry* grown = realloc(emu->log, cap * sizeof(*grown));
		if (!grown) {
			++emu->log_dropped;
			free(text);
			return;
		}
		emu->log = grown;
		emu->log_cap = cap;
	}
	emu->log[emu->log_len].level = level;
	emu->log[emu->log_len].category = category;
	emu->log[emu->log_len].text = text;
	++emu->log_len;
}

static void pc_log_callback(struct mLogger* logger, int category, enum mLogLevel level,
                            const char* format, va_list args) {
	(void) logger;
	pc_emu* emu = pc_current;
	if (!emu) {
		/* A memory probe (see pc_emu_read8), or libmgba logging outside any shim call: dropping
		 * is better than attributing the line to the wrong emulator. */
		return;
	}
	va_list measure;
	va_copy(measure, args);
	int needed = vsnprintf(NULL, 0, format, measure);
	va_end(measure);
	if (needed < 0) {
		needed = 0;
	}
	char* text = malloc((size_t) needed + 1);
	if (!text) {
		++emu->log_dropped;
		return;
	}
	vsnprintf(text, (size_t) needed + 1, format, args);
	const char* name = mLogCategoryName(category);
	pc_log_push(emu, (int) level, name ? name : "unknown", text);
}

/* No filter: every category and level reaches the callback; the Rust side filters. */
static struct mLogger pc_logger = { .log = pc_log_callback, .filter = NULL };
static pthread_once_t pc_logger_once = PTHREAD_ONCE_INIT;

static void pc_install_logger(void) {
	mLogSetDefaultLogger(&pc_logger);
}

/* Brackets every entry point so that lines logged during the call land in `emu`. Saving the
 * previous value keeps nested use (one emulator's call inside another's, not done today) sane. */
#define PC_ENTER(emu)                  \
	pc_emu* pc_previous = pc_current; \
	pc_current = (emu)
#define PC_LEAVE() pc_current = pc_previous

/* Reasons name no path: the Rust side puts the path in its own message. */
static void pc_set_error(char* err, size_t err_len, const char* reason) {
	if (err && err_len) {
		snprintf(err, err_len, "%s", reason);
	}
}

pc_emu* pc_emu_create(const char* path, int as_cartridge, char* err, size_t err_len) {
	pthread_once(&pc_logger_once, pc_install_logger);
	if (err && err_len) {
		err[0] = '\0';
	}

	pc_emu* emu = calloc(1, sizeof(*emu));
	if (!emu) {
		pc_set_error(err, err_len, "out of memory");
		return NULL;
	}
	PC_ENTER(emu);

	/* mCoreFind runs every core's isROM over the file: NULL means mGBA does not recognise it. */
	struct mCore* core = mCoreFind(path);
	if (!core) {
		pc_set_error(err, err_len, "mGBA does not recognise it as a GBA ROM or ELF");
		goto fail;
	}
	if (core->platform(core) != mPLATFORM_GBA) {
		pc_set_error(err, err_len, "mGBA takes it for a ROM of another system");
		free(core); /* an uninitialised core owns nothing else */
		goto fail;
	}
	if (!core->init(core)) {
		pc_set_error(err, err_len, "mGBA failed to initialise a GBA core");
		free(core);
		goto fail;
	}
	emu->core = core;

	/* A NULL port keeps mGBA away from the user's config files: runs are reproducible. The
	 * options therefore stay zero: no BIOS file, so mGBA's built-in HLE BIOS boots the cartridge;
	 * no audio/video sync, so nothing waits for a device. Audio samples pile up in mGBA's own
	 * buffers, which stop accepting samples when full, and are never played. */
	mCoreInitConfig(core, NULL);

	/* Without an output buffer the GBA core keeps its renderer detached and draws nothing. The
	 * stride is in pixels (color_t units), not bytes. */
	emu->video = calloc((size_t) PC_SCREEN_WIDTH * PC_SCREEN_HEIGHT, sizeof(color_t));
	if (!emu->video) {
		pc_set_error(err, err_len, "out of memory");
		goto fail;
	}
	core->setVideoBuffer(core, emu->video, PC_SCREEN_WIDTH);

	struct VFile* vf = VFileOpen(path, O_RDONLY);
	if (!vf) {
		pc_set_error(err, err_len, "mGBA cannot open the file");
		goto fail;
	}
	/* mCoreLoadFile would let core->loadROM guess: an image of 256 KiB or less whose code at 0xC0
	 * branches forward, or loads an EWRAM address with `LDR rX, [pc, #n]` early on, is taken for
	 * a multiboot image and copied to EWRAM, leaving the cartridge empty. A real GBA boots a
	 * cartridge as a cartridge, so cartridge images go straight to GBALoadROM. */
	bool loaded = as_cartridge ? GBALoadROM(core->board, vf) : core->loadROM(core, vf);
	if (!loaded) {
		vf->close(vf); /* on success the core owns it */
		pc_set_error(err, err_len, "mGBA failed to load it");
		goto fail;
	}
	core->reset(core);

	PC_LEAVE();
	return emu;

fail:
	PC_LEAVE();
	pc_emu_destroy(emu);
	return NULL;
}

void pc_emu_destroy(pc_emu* emu) {
	if (!emu) {
		return;
	}
	PC_ENTER(emu);
	if (emu->core) {
		mCoreConfigDeinit(&emu->core->config);
		emu->core->deinit(emu->core); /* unloads the ROM and frees the core itself */
		emu->core = NULL;
	}
	PC_LEAVE();
	free(emu->video);
	free(emu->profile_samples);
	pc_emu_log_clear(emu);
	free(emu->log);
	free(emu);
}

void pc_emu_set_keys(pc_emu* emu, uint32_t keys) {
	PC_ENTER(emu);
	emu->core->setKeys(emu->core, keys & 0x3FF);
	PC_LEAVE();
}

/* mGBA's software renderer skips a scanline it believes unchanged since it last drew it (a
 * per-line cache of the video registers plus dirty bits), leaving the old pixels in the output
 * buffer. With libmgba 0.10.1 that bookkeeping goes out of step right after reset: the BIOS skip
 * starts the machine at VCOUNT 126 while the renderer's idea of the next line starts at 0, and
 * line 126 then keeps the white of forced blank for as long as the picture stays the same.
 * Marking every line dirty before each frame makes each frame a full, honest redraw; the cost
 * does not matter here. */
static void pc_force_full_redraw(pc_emu* emu) {
	struct GBA* gba = emu->core->board;
	struct GBAVideoRenderer* renderer = gba->video.renderer;
	const void* pixels = NULL;
	size_t stride = 0;
	renderer->getPixels(renderer, &stride, &pixels);
	/* Only the software renderer hands out our buffer; never poke another renderer's fields. */
	if (pixels == emu->video) {
		struct GBAVideoSoftwareRenderer* software = (struct GBAVideoSoftwareRenderer*) renderer;
		memset(software->scanlineDirty, 0xFF, sizeof(software->scanlineDirty));
	}
}

void pc_emu_run_frame(pc_emu* emu) {
	PC_ENTER(emu);
	pc_force_full_redraw(emu);
	emu->core->runFrame(emu->core);
	PC_LEAVE();
}

const uint32_t* pc_emu_frame(const pc_emu* emu) {
	_Static_assert(sizeof(color_t) == sizeof(uint32_t), "libmgba built with COLOR_16_BIT");
	return (const uint32_t*) emu->video;
}

/* rawRead* with segment -1 reads what the CPU would see, without I/O side effects or timing.
 * mGBA may log while doing so (e.g. "Bad memory Load" for unmapped addresses): those lines are
 * about the harness's probe, not the ROM's behaviour, so they are routed nowhere (NULL) rather
 * than into the emulator's log where they could look like a ROM failure. */
uint32_t pc_emu_read8(pc_emu* emu, uint32_t address) {
	PC_ENTER(NULL);
	uint32_t value = emu->core->rawRead8(emu->core, address, -1);
	PC_LEAVE();
	return value & 0xFF;
}

uint32_t pc_emu_read16(pc_emu* emu, uint32_t address) {
	PC_ENTER(NULL);
	uint32_t value = emu->core->rawRead16(emu->core, address, -1);
	PC_LEAVE();
	return value & 0xFFFF;
}

uint32_t pc_emu_read32(pc_emu* emu, uint32_t address) {
	PC_ENTER(NULL);
	uint32_t value = emu->core->rawRead32(emu->core, address, -1);
	PC_LEAVE();
	return value;
}

void pc_emu_read_bytes(pc_emu* emu, uint32_t address, uint8_t* out, size_t len) {
	PC_ENTER(NULL);
	for (size_t i = 0; i < len; ++i) {
		out[i] = (uint8_t) emu->core->rawRead8(emu->core, address + (uint32_t) i, -1);
	}
	PC_LEAVE();
}

/* rawWrite* with segment -1 patch memory as a debugger would: no timing, no I/O side effects.
 * For setting up memory contents, e.g. the random RAM of a cold boot, before the ROM runs.
 * Aligned words go through rawWrite32: libmgba 0.10's byte patch ignores palette RAM and OAM,
 * its word patch covers every RAM region. */
void pc_emu_write_bytes(pc_emu* emu, uint32_t address, const uint8_t* bytes, size_t len) {
	PC_ENTER(NULL);
	size_t i = 0;
	while (i < len) {
		uint32_t at = address + (uint32_t) i;
		if ((at & 3) == 0 && len - i >= 4) {
			uint32_t word = (uint32_t) bytes[i] | ((uint32_t) bytes[i + 1] << 8) |
			                ((uint32_t) bytes[i + 2] << 16) | ((uint32_t) bytes[i + 3] << 24);
			emu->core->rawWrite32(emu->core, at, -1, word);
			i += 4;
		} else if ((at & 1) == 0 && len - i >= 2) {
			emu->core->rawWrite16(emu->core, at, -1, (uint16_t) (bytes[i] | (bytes[i + 1] << 8)));
			i += 2;
		} else {
			emu->core->rawWrite8(emu->core, at, -1, bytes[i]);
			i += 1;
		}
	}
	PC_LEAVE();
}

uint64_t pc_emu_cycles(const pc_emu* emu) {
	return mTimingGlobalTime(emu->core->timing);
}

uint32_t pc_emu_frame_counter(pc_emu* emu) {
	return emu->core->frameCounter(emu->core);
}

size_t pc_emu_log_count(const pc_emu* emu) {
	return emu->log_len;
}

int pc_emu_log_entry(const pc_emu* emu, size_t index, int* level, const char** category,
                     const char** text) {
	if (index >= emu->log_len) {
		return 0;
	}
	*level = emu->log[index].level;
	*category = emu->log[index].category;
	*text = emu->log[index].text;
	return 1;
}

size_t pc_emu_log_dropped(const pc_emu* emu) {
	return emu->log_dropped;
}

void pc_emu_log_clear(pc_emu* emu) {
	for (size_t i = 0; i < emu->log_len; ++i) {
		free(emu->log[i].text);
	}
	emu->log_len = 0;
	emu->log_dropped = 0;
}

/* The profiler's event: runs between two instructions, so r15 is the next instruction plus the
 * pipeline offset (8 in ARM state, 4 in Thumb); the true address is stored with bit 0 set for
 * Thumb, as in an interworking address. */
static void pc_profile_tick(struct mTiming* timing, void* context, uint32_t cycles_late) {
	pc_emu* emu = context;
	struct ARMCore* cpu = emu->core->cpu;
	int thumb = cpu->executionMode == MODE_THUMB;
	uint32_t pc = (uint32_t) cpu->gprs[15] - (thumb ? 4u : 8u);
	if (emu->profile_len == emu->profile_cap) {
		size_t cap = emu->profile_cap ? emu->profile_cap * 2 : 4096;
		uint32_t* grown = realloc(emu->profile_samples, cap * 2 * sizeof(uint32_t));
		if (grown) {
			emu->profile_samples = grown;
			emu->profile_cap = cap;
		}
	}
	if (emu->profile_len < emu->profile_cap) {
		emu->profile_samples[2 * emu->profile_len] = pc | (uint32_t) thumb;
		emu->profile_samples[2 * emu->profile_len + 1] = (uint32_t) cpu->gprs[14];
		++emu->profile_len;
	}
	int32_t next = (int32_t) emu->profile_period - (int32_t) cycles_late;
	mTimingSchedule(timing, &emu->profile_event, next > 1 ? next : 1);
}

void pc_emu_profile_start(pc_emu* emu, uint32_t period) {
	PC_ENTER(emu);
	if (emu->profile_period) {
		mTimingDeschedule(emu->core->timing, &emu->profile_event);
	}
	emu->profile_period = period ? period : 1;
	emu->profile_event.context = emu;
	emu->profile_event.callback = pc_profile_tick;
	emu->profile_event.name = "portalcast profiler";
	emu->profile_event.priority = 0x7F;
	mTimingSchedule(emu->core->timing, &emu->profile_event, (int32_t) emu->profile_period);
	PC_LEAVE();
}

void pc_emu_profile_stop(pc_emu* emu) {
	PC_ENTER(emu);
	if (emu->profile_period) {
		mTimingDeschedule(emu->core->timing, &emu->profile_event);
		emu->profile_period = 0;
	}
	PC_LEAVE();
}

size_t pc_emu_profile_samples(const pc_emu* emu, const uint32_t** pairs) {
	*pairs = emu->profile_samples;
	return emu->profile_len;
}

void pc_emu_profile_clear(pc_emu* emu) {
	emu->profile_len = 0;
}
