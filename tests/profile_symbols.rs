//! The profiler's symbol lookup on the real ROM: the renderer's IWRAM code and the math
//! benchmark's overlay share addresses (linker.ld's `OVERLAY`), and so do the lit and the unlit
//! kernel banks; `pc-profile` must name each address by the code that runs there in the scene it
//! profiles, or it charges the renderer's cycles to benchmark loops that never run in the game,
//! and a lit kernel's to an unlit one.

use portalcast_harness::symbols::{FunctionSymbols, Overlays};

/// IWRAM's address range.
const IWRAM: std::ops::Range<u32> = 0x0300_0000..0x0300_8000;

fn iwram_names(symbols: &FunctionSymbols) -> Vec<&str> {
    symbols
        .all()
        .iter()
        .filter(|(start, _, _)| IWRAM.contains(start))
        .map(|(_, _, name)| name.as_str())
        .collect()
}

#[test]
fn iwram_addresses_are_named_by_the_code_the_profiled_scene_runs() {
    portalcast_xtask::rom_for_tests();
    let elf = portalcast_xtask::elf_path();
    let load = |overlays| {
        FunctionSymbols::load(&elf, overlays).unwrap_or_else(|problem| panic!("{problem}"))
    };
    let game = load(Overlays::default());
    let math = load(Overlays {
        math: true,
        ..Overlays::default()
    });
    let unlit = load(Overlays {
        unlit_kernels: true,
        ..Overlays::default()
    });
    let pairs = load(Overlays {
        pair_kernels: true,
        ..Overlays::default()
    });
    let is_math = |name: &&str| name.contains("math_bench") || name.starts_with("pc_mb_");
    let is_render_walk = |name: &&str| name.contains("portalcast::render::walk::Renderer");

    let game_names = iwram_names(&game);
    assert!(game_names.iter().any(is_render_walk), "{game_names:?}");
    assert!(!game_names.iter().any(is_math), "{game_names:?}");
    let math_names = iwram_names(&math);
    assert!(math_names.iter().any(is_math), "{math_names:?}");
    assert!(!math_names.iter().any(is_render_walk), "{math_names:?}");

    // The same address, the overlay's first instruction, under each name.
    let (start, _, _) = game
        .all()
        .iter()
        .find(|(_, _, name)| is_render_walk(&name.as_str()))
        .expect("a walk function");
    assert!(game
        .lookup(*start)
        .is_some_and(|name| name.contains("render")));
    assert!(math
        .lookup(*start)
        .is_none_or(|name| !name.contains("render")));

    // The kernel banks: lit names by default, unlit ones on request; the doubled column
    // kernels by default, the pair ones on request; each at the same addresses as the other.
    let lit_kernel = |name: &str| name.starts_with("pc_col_") && name.contains("_lit_");
    let unlit_kernel = |name: &str| name.starts_with("pc_col_") && name.contains("_unlit_");
    banks_are_named_apart(&game, &unlit, lit_kernel, unlit_kernel);
    let doubled = |name: &str| name.starts_with("pc_col_dbl_");
    let paired = |name: &str| name.starts_with("pc_col_pair_");
    banks_are_named_apart(&game, &pairs, doubled, paired);
}

/// `default` names kernels of one bank (`in_default`) and none of another (`in_other`), whose
/// names `other` gives instead, at the same addresses.
fn banks_are_named_apart(
    default: &FunctionSymbols,
    other: &FunctionSymbols,
    in_default: impl Fn(&str) -> bool,
    in_other: impl Fn(&str) -> bool,
) {
    names_one_bank(&iwram_names(default), &in_default, &in_other);
    names_one_bank(&iwram_names(other), &in_other, &in_default);
    let (start, _, _) = default
        .all()
        .iter()
        .find(|(_, _, name)| in_default(name))
        .expect("a kernel of the default bank");
    assert!(other.lookup(*start).is_none_or(|name| !in_default(name)));
}

/// `names` include some that `shown` picks and none that `hidden` picks.
fn names_one_bank(names: &[&str], shown: &impl Fn(&str) -> bool, hidden: &impl Fn(&str) -> bool) {
    assert!(names.iter().any(|name| shown(name)), "{names:?}");
    assert!(!names.iter().any(|name| hidden(name)), "{names:?}");
}
