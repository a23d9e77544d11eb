//! The math micro-benchmark in the real mGBA core (the ROM's math scene, L held at power-on):
//! every variant of every operation returns what the engine's Rust function returns on the
//! host, pair by pair (the ARM routines of `asm/mathbench.s` included: each asm routine has a
//! Rust twin), and the figures it prints are complete and keep the relations that any correct
//! measurement keeps. The figures themselves go to `docs/BENCH.md` through `cargo bench-math`.

mod common;

use common::*;
use portalcast::math_bench::{mix, Op};
use portalcast_harness::Keys;
use std::sync::OnceLock;

/// Frames the scene may take (it needs a few dozen).
const FRAME_LIMIT: u32 = 1200;

/// The ROM's debug lines from one run of the math scene, shared by the tests of this file.
fn math_lines() -> &'static [String] {
    static LINES: OnceLock<Vec<String>> = OnceLock::new();
    LINES.get_or_init(|| {
        let mut emulator = boot();
        // L alone held at power-on selects the math scene.
        emulator.set_keys(Keys::L);
        emulator
            .run_frames(4)
            .unwrap_or_else(|error| panic!("{error}"));
        emulator.set_keys(Keys::NONE);
        let mut frames = 4;
        while !emulator.debug_lines().contains(&"math done") {
            assert!(
                frames < FRAME_LIMIT,
                "no `math done` after {FRAME_LIMIT} frames"
            );
            emulator
                .run_frames(10)
                .unwrap_or_else(|error| panic!("{error}"));
            frames += 10;
        }
        emulator
            .debug_lines()
            .into_iter()
            .map(str::to_owned)
            .collect()
    })
}

/// The line starting with `prefix` that names `op`.
fn line_for(prefix: &str, op: Op) -> &'static str {
    math_lines()
        .iter()
        .find(|line| line.starts_with(prefix) && field(line, "op") == Some(op.name()))
        .unwrap_or_else(|| panic!("no `{prefix} op={}` line", op.name()))
}

#[test]
fn every_variant_returns_what_the_rust_function_returns() {
    for op in Op::ALL {
        let line = line_for("math-check ", op);
        let expected = mix(op.inputs().iter().map(|&[a, b]| op.twin(a, b)));
        let expected = format!("0x{expected:08x}");
        assert_eq!(
            field(line, "rom"),
            Some(expected.as_str()),
            "Thumb in ROM: {line}"
        );
        assert_eq!(
            field(line, "iwram"),
            Some(expected.as_str()),
            "Thumb in IWRAM: {line}"
        );
        let arm = field(line, "arm");
        if op.has_arm() {
            assert_eq!(arm, Some(expected.as_str()), "ARM routine: {line}");
        } else {
            assert_eq!(arm, Some("-"), "{line}");
        }
    }
}

/// An operation's figures: cycles ×100 in ROM, in IWRAM, and of the ARM routine if any.
fn figures(op: Op) -> (u64, u64, Option<u64>) {
    let line = line_for("math-cycles-x100 ", op);
    let arm = match field(line, "arm") {
        Some("-") => None,
        _ => Some(number(line, "arm")),
    };
    assert_eq!(arm.is_some(), op.has_arm(), "{line}");
    (number(line, "rom"), number(line, "iwram"), arm)
}

/// The math scene's stack stays inside the linker script's `STACK_RESERVE`, like every scene's:
/// its code overlay runs over the renderer's code, not in the stack's room, so the boot paint
/// from the end of `.bss` up tells how deep the scene went (`stack used=… room=… reserve=…`,
/// printed before `math done`).
#[test]
fn the_math_scene_stack_stays_in_its_reserve() {
    let line = checked_stack_line(math_lines().iter().map(String::as_str), "the math scene");
    println!("math scene: {line}");
}

#[test]
fn every_operation_is_timed_and_the_figures_are_consistent() {
    let begin = math_lines()
        .iter()
        .find(|line| line.starts_with("math begin "))
        .expect("a `math begin` line");
    println!("{begin}");
    let (loop_rom, loop_iwram, loop_arm) = figures(Op::Loop);
    for op in Op::ALL {
        let (rom, iwram, arm) = figures(op);
        println!(
            "{:12} ROM {:>8.2}  IWRAM {:>8.2}  ARM {}",
            op.name(),
            rom as f64 / 100.0,
            iwram as f64 / 100.0,
            arm.map_or("-".to_string(), |arm| format!("{:.2}", arm as f64 / 100.0)),
        );
        assert!(rom > 0 && iwram > 0 && arm != Some(0), "{op:?}");
        // The same instructions fetched from IWRAM (one cycle) instead of the cart (wait states).
        assert!(iwram < rom, "{op:?}: IWRAM {iwram} not below ROM {rom}");
        // Every loop does at least what the bare loop does.
        if op != Op::Loop {
            assert!(
                rom > loop_rom && iwram > loop_iwram,
                "{op:?} below the bare loop"
            );
            if let (Some(arm), Some(loop_arm)) = (arm, loop_arm) {
                assert!(arm > loop_arm, "{op:?}: ARM below the bare loop");
            }
        }
    }
    // A 64-bit product is one SMULL in ARM and a library call in Thumb.
    for op in [Op::MulFx24_8, Op::MulFx16_16] {
        let (rom, iwram, arm) = figures(op);
        let arm = arm.expect("an ARM multiply");
        assert!(arm < iwram && iwram < rom, "{op:?}: {rom} {iwram} {arm}");
    }
    // The reciprocal by table and Newton step beats the 64-bit divide it replaces.
    assert!(figures(Op::Recip).1 < figures(Op::RecipExact).1);
}
