//! The headless runner binary, end to end.

mod common;

use std::process::{Command, Output};

use common::*;

fn pc_run(args: &[&std::ffi::OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pc-run"))
        .args(args)
        .output()
        .expect("run pc-run")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn runs_a_rom_prints_debug_lines_and_writes_frames() {
    let scratch = Scratch::new("pc-run-ok");
    let rom = write_rom(&scratch, "hello.gba", |asm| {
        asm.debug_print("hello from pc-run", LEVEL_INFO);
        asm.store16(0x0500_0000, 0x7C00); // blue backdrop
        asm.store16(DISPCNT, 0);
        asm.halt();
    });
    let out = scratch.path().join("frames");
    let output = pc_run(&[
        rom.as_os_str(),
        "--frames".as_ref(),
        "5".as_ref(),
        "--png-every".as_ref(),
        "2".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    assert_eq!(text(&output.stdout), "hello from pc-run\n");
    let mut written: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().into_string().unwrap())
        .collect();
    written.sort();
    assert_eq!(
        written,
        ["frame-000002.png", "frame-000004.png", "frame-000005.png"]
    );
    let last = image::open(out.join("frame-000005.png")).unwrap().to_rgb8();
    assert_eq!(last.dimensions(), (240, 160));
    assert_eq!(last.get_pixel(120, 80).0, [0, 0, 255]);
}

#[test]
fn key_script_file_is_applied() {
    let scratch = Scratch::new("pc-run-keys");
    // Prints "A" once KEYINPUT shows A held (bit 0 clear), then stops.
    let rom = write_rom(&scratch, "keys.gba", |asm| {
        asm.ldr_const(4, KEYINPUT);
        let wait = asm.here();
        asm.ldrh(5, 4);
        asm.tst_imm(5, 1);
        asm.bne(wait);
        asm.debug_print("A pressed", LEVEL_INFO);
        asm.halt();
    });
    let frames = scratch.path().join("frames");
    let untouched = pc_run(&[
        rom.as_os_str(),
        "--frames".as_ref(),
        "6".as_ref(),
        "--out".as_ref(),
        frames.as_os_str(),
    ]);
    assert!(untouched.status.success(), "{}", text(&untouched.stderr));
    assert_eq!(text(&untouched.stdout), "", "the ROM waits for A");

    let keys = scratch.write("keys.txt", b"# press A late\n3: A\n");
    let output = pc_run(&[
        rom.as_os_str(),
        "--frames".as_ref(),
        "6".as_ref(),
        "--png-every".as_ref(),
        "0".as_ref(),
        "--keys".as_ref(),
        keys.as_os_str(),
        "--out".as_ref(),
        frames.as_os_str(),
    ]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    assert_eq!(text(&output.stdout), "A pressed\n");
}

#[test]
fn summary_aggregates_cycle_fields() {
    let scratch = Scratch::new("pc-run-summary");
    let rom = write_rom(&scratch, "cycles.gba", |asm| {
        asm.debug_print("shown frame=1 draw_cycles=100 phase=3", LEVEL_INFO);
        asm.debug_print("shown frame=2 draw_cycles=300 phase=4", LEVEL_INFO);
        asm.debug_print("kernel cycles=28090", LEVEL_INFO);
        asm.halt();
    });
    let output = pc_run(&[
        rom.as_os_str(),
        "--frames".as_ref(),
        "3".as_ref(),
        "--summary".as_ref(),
        "--out".as_ref(),
        scratch.path().join("frames").as_os_str(),
    ]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    let stdout = text(&output.stdout);
    assert!(stdout.contains("summary: 3 frames, "), "{stdout}");
    assert!(
        stdout.contains(
            "  cycles: 1 samples, min 28090, mean 28090, max 28090 (mean 10.0% of a frame)"
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains("  draw_cycles: 2 samples, min 100, mean 200, max 300"),
        "{stdout}"
    );
    assert!(!stdout.contains("phase:"), "{stdout}");
}

#[test]
fn rom_panic_exits_non_zero_with_the_message() {
    let scratch = Scratch::new("pc-run-panic");
    let rom = write_rom(&scratch, "panic.gba", |asm| {
        asm.debug_print("panic: out of sectors at src/walk.rs:7", LEVEL_ERROR);
        asm.halt();
    });
    let out = scratch.path().join("frames");
    let output = pc_run(&[rom.as_os_str(), "--out".as_ref(), out.as_os_str()]);
    assert_eq!(output.status.code(), Some(1));
    assert_eq!(
        text(&output.stdout),
        "panic: out of sectors at src/walk.rs:7\n"
    );
    let stderr = text(&output.stderr);
    assert!(
        stderr.contains("panicked during frame 1: out of sectors at src/walk.rs:7"),
        "{stderr}"
    );
    assert!(
        out.join("frame-000001.png").exists(),
        "the failing frame is kept"
    );
}

#[test]
fn missing_rom_exits_non_zero_and_says_how_to_build_it() {
    let scratch = Scratch::new("pc-run-missing");
    let rom = scratch.path().join("portalcast.gba");
    let output = pc_run(&[rom.as_os_str()]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = text(&output.stderr);
    assert!(
        stderr.contains("does not exist") && stderr.contains("cargo rom"),
        "{stderr}"
    );
}

#[test]
fn bad_key_script_names_file_and_line() {
    let scratch = Scratch::new("pc-run-bad-keys");
    let rom = write_rom(&scratch, "rom.gba", |asm| asm.halt());
    let keys = scratch.write("keys.txt", b"1: A\n2: FIRE\n");
    let output = pc_run(&[rom.as_os_str(), "--keys".as_ref(), keys.as_os_str()]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = text(&output.stderr);
    assert!(stderr.contains("keys.txt: key script line 2:"), "{stderr}");
}

#[test]
fn bad_arguments_print_usage() {
    for args in [
        &[][..],
        &["rom.gba", "--frames"][..],
        &["rom.gba", "--frames", "many"][..],
        &["rom.gba", "--speed", "2"][..],
        &["a.gba", "b.gba"][..],
    ] {
        let args: Vec<&std::ffi::OsStr> = args.iter().map(|arg| arg.as_ref()).collect();
        let output = pc_run(&args);
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        assert!(
            text(&output.stderr).contains("usage: pc-run ROM"),
            "{args:?}"
        );
    }
}
