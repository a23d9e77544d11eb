//! A missing, empty or wrong ROM file is a clear error naming the file and the fix, never a crash.

mod common;

use common::{gba_elf, gba_rom, Asm, Scratch};
use portalcast_harness::{Emulator, HarnessError};

fn load_error(path: &std::path::Path) -> HarnessError {
    Emulator::load(path).expect_err("loading must fail")
}

fn assert_helpful(error: &HarnessError, path: &std::path::Path) {
    let message = error.to_string();
    assert!(
        message.contains(&path.display().to_string()),
        "message does not name the file: {message}"
    );
    assert!(
        message.contains("cargo rom"),
        "message does not say how to build the ROM: {message}"
    );
}

#[test]
fn missing_rom_names_the_path_and_the_build_command() {
    let scratch = Scratch::new("missing");
    let path = scratch.path().join("nowhere.gba");
    let error = load_error(&path);
    assert!(
        matches!(error, HarnessError::RomNotFound { .. }),
        "{error:?}"
    );
    assert_helpful(&error, &path);
}

#[test]
fn empty_file_is_rejected() {
    let scratch = Scratch::new("empty");
    let path = scratch.write("empty.gba", b"");
    let error = load_error(&path);
    assert!(matches!(error, HarnessError::RomEmpty { .. }), "{error:?}");
    assert_helpful(&error, &path);
}

#[test]
fn short_text_file_is_rejected() {
    let scratch = Scratch::new("short-text");
    let path = scratch.write("notes.gba", b"this is not a ROM\n");
    let error = load_error(&path);
    assert!(matches!(error, HarnessError::NotARom { .. }), "{error:?}");
    assert_helpful(&error, &path);
    assert!(error.to_string().contains("fewer than"), "{error}");
}

#[test]
fn long_text_file_is_rejected() {
    let scratch = Scratch::new("long-text");
    let text = "All work and no play makes a dull ROM.\n".repeat(20);
    let path = scratch.write("readme.txt", text.as_bytes());
    let error = load_error(&path);
    assert!(matches!(error, HarnessError::NotARom { .. }), "{error:?}");
    assert_helpful(&error, &path);
    assert!(error.to_string().contains("branch"), "{error}");
}

#[test]
fn directory_is_rejected() {
    let scratch = Scratch::new("directory");
    let error = load_error(scratch.path());
    assert!(matches!(error, HarnessError::NotARom { .. }), "{error:?}");
    assert_helpful(&error, scratch.path());
}

#[test]
fn header_without_fixed_byte_and_with_a_logo_is_rejected() {
    let scratch = Scratch::new("bad-header");
    let mut rom = gba_rom(&Asm::new().finish());
    rom[0xB2] = 0;
    rom[0x10] = 0x42; // a non-blank logo: mGBA then insists on 0x96
    let path = scratch.write("unfixed.gba", &rom);
    let error = load_error(&path);
    assert!(matches!(error, HarnessError::NotARom { .. }), "{error:?}");
    assert!(error.to_string().contains("0xb2"), "{error}");
}

#[test]
fn elf_for_another_machine_is_rejected() {
    let scratch = Scratch::new("elf-machine");
    let mut elf = gba_elf(&gba_rom(&Asm::new().finish()));
    elf[0x12] = 62; // EM_X86_64
    let path = scratch.write("host.elf", &elf);
    let error = load_error(&path);
    assert!(matches!(error, HarnessError::NotARom { .. }), "{error:?}");
    assert!(error.to_string().contains("not ARM"), "{error}");
}

#[test]
fn elf_with_a_foreign_entry_point_is_rejected() {
    let scratch = Scratch::new("elf-entry");
    let mut elf = gba_elf(&gba_rom(&Asm::new().finish()));
    elf[0x18..0x1C].copy_from_slice(&0x0300_0000u32.to_le_bytes());
    let path = scratch.write("iwram.elf", &elf);
    let error = load_error(&path);
    assert!(
        error.to_string().contains("entry point is 0x03000000"),
        "{error}"
    );
}

#[test]
fn errors_are_std_errors() {
    let scratch = Scratch::new("std-error");
    let error: Box<dyn std::error::Error> = Box::new(load_error(&scratch.path().join("gone.gba")));
    assert!(error.to_string().starts_with("ROM "));
}

/// A file that passes the harness's own checks can still be refused by mGBA: here an image whose
/// first seven words are all branches, which mGBA takes for a BIOS dump rather than a game.
#[test]
fn mgba_refusal_is_reported_not_crashed_on() {
    let scratch = Scratch::new("bios-like");
    let mut rom = gba_rom(&Asm::new().finish());
    for vector in 1..7 {
        rom[vector * 4..vector * 4 + 4].copy_from_slice(&0xEA00_0000u32.to_le_bytes());
    }
    let path = scratch.write("bios-like.gba", &rom);
    let error = load_error(&path);
    assert!(
        matches!(error, HarnessError::MgbaRejected { .. }),
        "{error:?}"
    );
    let message = error.to_string();
    assert!(message.contains("does not recognise it"), "{message}");
    assert_helpful(&error, &path);
}
