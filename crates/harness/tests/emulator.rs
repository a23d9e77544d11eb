//! The harness against the real mGBA core, with tiny hand-assembled ROMs (see `common`).

mod common;

use common::*;
use portalcast_harness::{Emulator, HarnessError, KeyScript, Keys, LogLevel};

/// Cycles in one GBA frame: 228 lines of 1232 cycles.
const CYCLES_PER_FRAME: u64 = 280_896;

fn hello_rom(scratch: &Scratch) -> std::path::PathBuf {
    write_rom(scratch, "hello.gba", |asm| {
        asm.debug_print("hello", LEVEL_INFO);
        asm.halt();
    })
}

#[test]
fn debug_prints_arrive_in_the_log() {
    let scratch = Scratch::new("hello");
    let mut emu = Emulator::load(&hello_rom(&scratch)).unwrap();
    emu.run_frames(2).unwrap();
    assert_eq!(emu.debug_lines(), ["hello"]);
    let line = emu
        .log_lines()
        .iter()
        .find(|line| line.is_debug_print())
        .unwrap();
    assert_eq!(line.category, "GBA Debug");
    assert_eq!(line.level, LogLevel::Info);
    assert_eq!(line.to_string(), "[GBA Debug] info: hello");

    let drained = emu.drain_log();
    assert!(drained.iter().any(|line| line.text == "hello"));
    assert!(emu.log_lines().is_empty());
    emu.run_frame().unwrap();
    assert!(emu.debug_lines().is_empty(), "a print is reported once");
}

#[test]
fn elf_files_load_too() {
    let scratch = Scratch::new("elf");
    let mut asm = Asm::new();
    asm.debug_print("hello from an ELF", LEVEL_INFO);
    asm.halt();
    let path = scratch.write("hello.elf", &gba_elf(&gba_rom(&asm.finish())));
    let mut emu = Emulator::load(&path).unwrap();
    emu.run_frame().unwrap();
    assert_eq!(emu.debug_lines(), ["hello from an ELF"]);
}

#[test]
fn fatal_print_fails_the_frame_and_emulation_can_go_on() {
    let scratch = Scratch::new("fatal");
    let rom = write_rom(&scratch, "fatal.gba", |asm| {
        asm.debug_print("boom", LEVEL_FATAL);
        asm.halt();
    });
    let mut emu = Emulator::load(&rom).unwrap();
    match emu.run_frames(5) {
        Err(HarnessError::RomFatal {
            frame,
            category,
            message,
        }) => {
            assert_eq!(frame, 1);
            assert_eq!(category, "GBA Debug");
            assert_eq!(message, "boom");
        }
        other => panic!("expected RomFatal, got {other:?}"),
    }
    assert_eq!(emu.frames_run(), 1, "run_frames stops at the failing frame");
    let error = emu.log_lines().last().unwrap();
    assert_eq!(error.level, LogLevel::Fatal);
    // mGBA does not halt on a fatal line: the next frames run normally.
    emu.run_frames(2).unwrap();
    assert_eq!(emu.frames_run(), 3);
}

#[test]
fn panic_print_is_reported_as_a_panic() {
    let scratch = Scratch::new("panic");
    let rom = write_rom(&scratch, "panic.gba", |asm| {
        asm.debug_print("starting", LEVEL_INFO);
        asm.debug_print("panic: index out of bounds at src/main.rs:42", LEVEL_ERROR);
        asm.halt();
    });
    let mut emu = Emulator::load(&rom).unwrap();
    let error = emu.run_frames(3).unwrap_err();
    match &error {
        HarnessError::RomPanicked { frame, message } => {
            assert_eq!(*frame, 1);
            assert_eq!(message, "index out of bounds at src/main.rs:42");
        }
        other => panic!("expected RomPanicked, got {other:?}"),
    }
    assert_eq!(
        error.to_string(),
        "the ROM panicked during frame 1: index out of bounds at src/main.rs:42"
    );
    assert_eq!(
        emu.debug_lines(),
        ["starting", "panic: index out of bounds at src/main.rs:42"]
    );
}

#[test]
fn a_panic_printed_at_fatal_level_is_still_a_panic() {
    let scratch = Scratch::new("fatal-panic");
    let rom = write_rom(&scratch, "panic.gba", |asm| {
        asm.debug_print("panic: boom at src/lib.rs:1", LEVEL_FATAL);
        asm.halt();
    });
    let mut emu = Emulator::load(&rom).unwrap();
    assert!(matches!(
        emu.run_frame(),
        Err(HarnessError::RomPanicked { .. })
    ));
}

/// gba's `MgbaBufferedLogger` sends a print at every newline, so core's two-line panic text
/// arrives as two prints; the harness joins them back.
#[test]
fn multi_line_panic_is_joined_back() {
    let scratch = Scratch::new("multi-line-panic");
    let rom = write_rom(&scratch, "panic.gba", |asm| {
        asm.debug_print("panic: panicked at src/main.rs:10:5:", LEVEL_FATAL);
        asm.debug_print("attempt to divide by zero", LEVEL_FATAL);
        asm.halt();
    });
    let mut emu = Emulator::load(&rom).unwrap();
    match emu.run_frame() {
        Err(HarnessError::RomPanicked { message, .. }) => assert_eq!(
            message,
            "panicked at src/main.rs:10:5:\nattempt to divide by zero"
        ),
        other => panic!("expected RomPanicked, got {other:?}"),
    }
}

#[test]
fn wild_jump_is_a_fatal_error() {
    let scratch = Scratch::new("wild");
    let rom = write_rom(&scratch, "wild.gba", |asm| {
        asm.ldr_const(0, 0x1000_0000); // nothing is mapped there
        asm.mov_pc(0);
    });
    let mut emu = Emulator::load(&rom).unwrap();
    match emu.run_frame() {
        Err(HarnessError::RomFatal {
            category, message, ..
        }) => {
            assert_eq!(category, "GBA Memory");
            assert!(message.contains("10000000"), "{message}");
        }
        other => panic!("expected RomFatal, got {other:?}"),
    }
}

/// Mode 3 (a 240x160 bitmap of BGR555 pixels), with known pixels at the corners.
fn bitmap_rom(scratch: &Scratch) -> std::path::PathBuf {
    write_rom(scratch, "bitmap.gba", |asm| {
        asm.store16(DISPCNT, 0x0403); // mode 3, BG2 on, forced blank off
        asm.store32(VRAM, 0x03E0_001F); // (0,0) red 0x001F, (1,0) green 0x03E0
        asm.store32(VRAM + 4, 0x7FFF_7C00); // (2,0) blue 0x7C00, (3,0) white
        asm.store32(VRAM + 2 * 240, 0x0000_7FFF); // (0,1) white: proves the row stride
        asm.store16(VRAM + 2 * (159 * 240 + 239), 0x001F); // (239,159) red
        asm.halt();
    })
}

#[test]
fn frame_is_240_by_160_with_red_in_the_first_channel() {
    let scratch = Scratch::new("colours");
    let mut emu = Emulator::load(&bitmap_rom(&scratch)).unwrap();
    emu.run_frames(2).unwrap();
    let frame = emu.frame_rgb();
    assert_eq!(frame.dimensions(), (240, 160));
    let pixel = |x, y| frame.get_pixel(x, y).0;
    let [r, g, b] = pixel(0, 0);
    assert!(
        r >= 248 && g == 0 && b == 0,
        "red came out as {:?}",
        [r, g, b]
    );
    assert_eq!(pixel(0, 0), [255, 0, 0], "5-bit 31 widens to 255");
    assert_eq!(pixel(1, 0), [0, 255, 0]);
    assert_eq!(pixel(2, 0), [0, 0, 255]);
    assert_eq!(pixel(3, 0), [255, 255, 255]);
    assert_eq!(pixel(4, 0), [0, 0, 0]);
    assert_eq!(pixel(0, 1), [255, 255, 255]);
    assert_eq!(pixel(1, 1), [0, 0, 0]);
    assert_eq!(pixel(239, 159), [255, 0, 0]);
}

/// Also a regression test: libmgba 0.10.1's renderer left line 126 (where emulation starts after
/// the BIOS skip) white for as long as the picture did not change; the shim forces full redraws.
#[test]
fn backdrop_colour_fills_the_screen() {
    let scratch = Scratch::new("backdrop");
    let rom = write_rom(&scratch, "backdrop.gba", |asm| {
        asm.store16(0x0500_0000, 0x001F); // palette colour 0 = pure red
        asm.store16(DISPCNT, 0x0000); // mode 0, no layers, forced blank off
        asm.halt();
    });
    let mut emu = Emulator::load(&rom).unwrap();
    for _ in 0..3 {
        emu.run_frames(2).unwrap();
        let frame = emu.frame_rgb();
        let wrong: Vec<_> = frame
            .enumerate_pixels()
            .filter(|(_, _, pixel)| pixel.0 != [255, 0, 0])
            .map(|(x, y, pixel)| (x, y, pixel.0))
            .take(5)
            .collect();
        assert!(wrong.is_empty(), "pixels not red: {wrong:?}");
    }
}

#[test]
fn saved_png_matches_the_frame() {
    let scratch = Scratch::new("png");
    let mut emu = Emulator::load(&bitmap_rom(&scratch)).unwrap();
    emu.run_frames(2).unwrap();
    let path = scratch.path().join("frame.png");
    emu.save_frame_png(&path).unwrap();
    let decoded = image::open(&path).unwrap().to_rgb8();
    assert_eq!(decoded, emu.frame_rgb());

    let error = emu
        .save_frame_png(&scratch.path().join("no/such/dir/frame.png"))
        .unwrap_err();
    assert!(matches!(error, HarnessError::Png { .. }), "{error:?}");
}

#[test]
fn memory_reads_see_what_the_rom_wrote() {
    let scratch = Scratch::new("memory");
    let rom = write_rom(&scratch, "memory.gba", |asm| {
        asm.store32(EWRAM, 0xDEAD_BEEF);
        asm.store16(EWRAM + 4, 0x1234);
        asm.store32(0x0300_0100, 0x0102_0304); // IWRAM
        asm.halt();
    });
    let mut emu = Emulator::load(&rom).unwrap();
    emu.run_frame().unwrap();
    assert_eq!(emu.read_u32(EWRAM), 0xDEAD_BEEF);
    assert_eq!(emu.read_u16(EWRAM), 0xBEEF);
    assert_eq!(emu.read_u8(EWRAM + 3), 0xDE);
    assert_eq!(emu.read_u16(EWRAM + 4), 0x1234);
    assert_eq!(
        emu.read_bytes(EWRAM, 6),
        [0xEF, 0xBE, 0xAD, 0xDE, 0x34, 0x12]
    );
    assert_eq!(emu.read_u32(0x0300_0100), 0x0102_0304);
    // The cartridge itself: the entry branch of the header.
    assert_eq!(emu.read_u32(ROM_BASE), 0xEA00_002E);
    assert_eq!(emu.read_bytes(ROM_BASE + 0xAC, 4), b"PCHT");
    // Probing unmapped memory is harmless and leaves no trace in the ROM's log.
    let before = emu.log_lines().len();
    let _ = emu.read_u32(0x1000_0000);
    emu.run_frame().unwrap();
    assert_eq!(emu.log_lines().len(), before);
}

/// mGBA would take this image (small, loading an EWRAM address early) for a multiboot program and
/// run it from EWRAM with an empty cartridge; as a `.gba` it must boot as a cartridge, while a
/// `.mb` file gets mGBA's detection.
#[test]
fn cartridge_images_are_never_mistaken_for_multiboot() {
    let scratch = Scratch::new("multiboot");
    let mut asm = Asm::new();
    asm.mov_imm(2, 0); // mGBA's multiboot scan skips the instruction at 0xC0
    asm.store32(EWRAM + 0x100, 0x600D_CAFE);
    asm.halt();
    let image = gba_rom(&asm.finish());

    let mut cartridge = Emulator::load(&scratch.write("small.gba", &image)).unwrap();
    cartridge.run_frame().unwrap();
    assert_eq!(cartridge.read_u32(ROM_BASE), 0xEA00_002E);
    assert_eq!(cartridge.read_u32(EWRAM), 0, "nothing copied to EWRAM");
    assert_eq!(cartridge.read_u32(EWRAM + 0x100), 0x600D_CAFE);

    let mut multiboot = Emulator::load(&scratch.write("small.mb", &image)).unwrap();
    multiboot.run_frame().unwrap();
    assert_eq!(
        multiboot.read_u32(EWRAM),
        0xEA00_002E,
        "image copied to EWRAM"
    );
    assert_ne!(multiboot.read_u32(ROM_BASE), 0xEA00_002E, "empty cartridge");
    assert_eq!(multiboot.read_u32(EWRAM + 0x100), 0x600D_CAFE);
}

/// Copies KEYINPUT to EWRAM forever, so the test can see what the ROM sees.
fn key_echo_rom(scratch: &Scratch) -> std::path::PathBuf {
    write_rom(scratch, "keys.gba", |asm| {
        asm.ldr_const(0, KEYINPUT);
        asm.ldr_const(2, EWRAM + 0x10);
        let top = asm.here();
        asm.ldrh(1, 0);
        asm.strh(1, 2);
        asm.b(top);
    })
}

#[test]
fn held_keys_reach_the_rom() {
    let scratch = Scratch::new("keys");
    let mut emu = Emulator::load(&key_echo_rom(&scratch)).unwrap();
    let seen = |emu: &Emulator| Keys::from_bits(!emu.read_u16(EWRAM + 0x10) & 0x3FF).unwrap();

    emu.run_frame().unwrap();
    assert_eq!(seen(&emu), Keys::NONE);
    emu.set_keys(Keys::A | Keys::UP | Keys::L);
    emu.run_frame().unwrap();
    assert_eq!(seen(&emu), Keys::A | Keys::UP | Keys::L);
    assert_eq!(
        emu.read_u16(EWRAM + 0x10),
        (Keys::A | Keys::UP | Keys::L).keyinput()
    );
    emu.set_keys(Keys::NONE);
    emu.run_frame().unwrap();
    assert_eq!(seen(&emu), Keys::NONE);
}

/// Documents what the `Keys` docs promise: no filtering of opposite d-pad directions.
#[test]
fn opposite_directions_reach_the_rom_unfiltered() {
    let scratch = Scratch::new("opposite");
    let mut emu = Emulator::load(&key_echo_rom(&scratch)).unwrap();
    let impossible = Keys::LEFT | Keys::RIGHT | Keys::UP | Keys::DOWN;
    emu.set_keys(impossible);
    emu.run_frame().unwrap();
    assert_eq!(emu.read_u16(EWRAM + 0x10), impossible.keyinput());
}

#[test]
fn key_script_drives_the_keys_frame_by_frame() {
    let scratch = Scratch::new("script");
    let mut emu = Emulator::load(&key_echo_rom(&scratch)).unwrap();
    let seen = |emu: &Emulator| Keys::from_bits(!emu.read_u16(EWRAM + 0x10) & 0x3FF).unwrap();
    let script = KeyScript::parse("1: A\n2-3: START+R\n").unwrap();

    let mut observed = Vec::new();
    for frames in 1..=5 {
        let mut emu_for_prefix = Emulator::load(emu.path()).unwrap();
        emu_for_prefix.run_script(&script, frames).unwrap();
        // run_script releases the keys afterwards, so read what the last frame saw first.
        observed.push(seen(&emu_for_prefix));
    }
    assert_eq!(
        observed,
        [
            Keys::NONE,
            Keys::A,
            Keys::START | Keys::R,
            Keys::START | Keys::R,
            Keys::NONE
        ]
    );

    emu.run_script(&script, 3).unwrap();
    assert_eq!(emu.keys(), Keys::NONE, "keys are released after the script");
    assert_eq!(emu.frames_run(), 3);
}

#[test]
fn cycles_advance_one_frame_at_a_time() {
    let scratch = Scratch::new("cycles");
    let mut emu = Emulator::load(&hello_rom(&scratch)).unwrap();
    assert_eq!(emu.cycles(), 0);
    emu.run_frame().unwrap();
    let first = emu.cycles();
    // mGBA's BIOS skip starts the machine part-way into a frame, so the first one is short.
    assert!(first > 0 && first < CYCLES_PER_FRAME, "{first}");
    emu.run_frames(10).unwrap();
    let per_frame = (emu.cycles() - first) as f64 / 10.0;
    assert!(
        (per_frame - CYCLES_PER_FRAME as f64).abs() < 16.0,
        "{per_frame} cycles per frame"
    );
    assert_eq!(emu.frames_run(), 11);
    assert_eq!(emu.mgba_frame_counter(), 11);
}

/// Many emulators on many threads at once, each flooding its log: every one must see exactly its
/// own lines (mGBA's logger is process-global; the shim routes by thread).
#[test]
fn concurrent_emulators_keep_their_own_logs() {
    const THREADS: usize = 8;
    const PRINTS: u8 = 200;
    let scratch = Scratch::new("threads");
    let roms: Vec<_> = (0..THREADS)
        .map(|index| {
            write_rom(&scratch, &format!("thread{index}.gba"), |asm| {
                asm.mov_imm(3, PRINTS);
                let top = asm.here();
                asm.debug_print(&format!("emulator {index}"), LEVEL_INFO);
                asm.subs_imm(3, 3, 1);
                asm.bne(top);
                asm.debug_print(&format!("emulator {index} done"), LEVEL_INFO);
                asm.halt();
            })
        })
        .collect();
    let barrier = std::sync::Barrier::new(THREADS);
    std::thread::scope(|scope| {
        for (index, rom) in roms.iter().enumerate() {
            let barrier = &barrier;
            scope.spawn(move || {
                let mut emu = Emulator::load(rom).unwrap();
                barrier.wait();
                emu.run_frames(3).unwrap();
                let lines = emu.debug_lines();
                let mine = format!("emulator {index}");
                assert_eq!(lines.len(), usize::from(PRINTS) + 1, "thread {index}");
                assert!(lines[..usize::from(PRINTS)]
                    .iter()
                    .all(|line| *line == mine));
                assert_eq!(lines[usize::from(PRINTS)], format!("{mine} done"));
            });
        }
    });
}

#[test]
fn an_emulator_can_move_between_threads() {
    let scratch = Scratch::new("move");
    let mut emu = Emulator::load(&hello_rom(&scratch)).unwrap();
    let emu = std::thread::spawn(move || {
        emu.run_frame().unwrap();
        emu
    })
    .join()
    .unwrap();
    assert_eq!(emu.debug_lines(), ["hello"]);
}
