//! A check of the linked ROM that the linker script cannot make itself: nothing the math
//! benchmark's overlay calls may lie in the code the overlay replaces.
//!
//! The overlay (`.bench_iwram`) runs over the renderer's code (`.iwram_render`, linker.ld): once
//! the math scene has loaded it, the bytes it covers hold the overlay, and the rest of
//! `.iwram_render` holds renderer code that nothing the math scene runs may depend on. The
//! script's NOCROSSREFS makes the linker refuse a direct reference between the two. It cannot
//! see lld's thunks: a call that needs a long-branch or interworking veneer (every call from
//! IWRAM to the ROM) goes through a thunk placed after the first caller's input sections, and lld
//! hands that one thunk to every later caller in range, whatever its section. A renderer call
//! to, say, `__aeabi_idiv` made first would put the thunk in `.iwram_render`, and the overlay's
//! own divide would jump there. So this decodes every branch of the overlay (ARM `B`/`BL`; Thumb
//! `B`, `B<cond>`, `BL`) and refuses one that leaves the overlay for `.iwram_render`, or that lands
//! on one of lld's thunks in `.iwram_render` under the overlay's own bytes.
//!
//! The kernel banks (the span kernels' `.iwram_kernels_lit` and `.iwram_kernels_unlit`, the
//! column kernels' four `.iwram_columns_*`) share their run addresses too, and one is copied
//! over another at run time: their code must branch only within its own bank, which this
//! checks the same way.
//!
//! Indirect jumps (`BX`, loads into `pc`) are not followed: the overlay's are returns, its jump
//! table and its own thunks, whose targets are in the ROM.

use object::{Object, ObjectSection, ObjectSymbol};

/// The section names of linker.ld.
const OVERLAY: &str = ".bench_iwram";
const REPLACED: &str = ".iwram_render";
/// The kernel banks, which share their run addresses (linker.ld).
const KERNEL_BANKS: [&str; 6] = [
    ".iwram_kernels_lit",
    ".iwram_kernels_unlit",
    ".iwram_columns_dbl_lit",
    ".iwram_columns_dbl_unlit",
    ".iwram_columns_pair_lit",
    ".iwram_columns_pair_unlit",
];

/// A range of run addresses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Span {
    pub start: u32,
    pub end: u32,
}

impl Span {
    fn contains(self, address: u32) -> bool {
        (self.start..self.end).contains(&address)
    }
}

/// What the code at an address is, after the ARM ELF mapping symbols (`$a`, `$t`, `$d`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Arm,
    Thumb,
    Data,
}

/// The branches in `code` (run from `at.start`), as (address of the branch, target), with
/// `modes` sorted by address (code before the first one is ARM).
pub fn branches(code: &[u8], at: Span, modes: &[(u32, Mode)]) -> Vec<(u32, u32)> {
    let mut found = Vec::new();
    let halfword = |address: u32| -> Option<u16> {
        let offset = (address - at.start) as usize;
        code.get(offset..offset + 2)
            .map(|bytes| u16::from_le_bytes([bytes[0], bytes[1]]))
    };
    let mut address = at.start;
    while address < at.end {
        let mode = modes
            .iter()
            .rev()
            .find(|(start, _)| *start <= address)
            .map_or(Mode::Arm, |&(_, mode)| mode);
        match mode {
            Mode::Data => address += 2,
            Mode::Arm if !address.is_multiple_of(4) => address += 2,
            Mode::Arm => {
                let (Some(low), Some(high)) = (halfword(address), halfword(address + 2)) else {
                    break;
                };
                let word = u32::from(low) | u32::from(high) << 16;
                if word >> 28 != 0xF && (word >> 25) & 7 == 0b101 {
                    let offset = sign_extend(word & 0x00FF_FFFF, 24) << 2;
                    found.push((address, address.wrapping_add(8).wrapping_add(offset as u32)));
                }
                address += 4;
            }
            Mode::Thumb => {
                let Some(first) = halfword(address) else {
                    break;
                };
                let pc = address.wrapping_add(4);
                let second = halfword(address + 2).unwrap_or(0);
                if first & 0xF800 == 0xF000 && second & 0xF800 == 0xF800 {
                    let offset = u32::from(first & 0x7FF) << 12 | u32::from(second & 0x7FF) << 1;
                    found.push((address, pc.wrapping_add(sign_extend(offset, 23) as u32)));
                    address += 4;
                    continue;
                }
                if first & 0xF800 == 0xE000 {
                    let offset = sign_extend(u32::from(first & 0x7FF) << 1, 12);
                    found.push((address, pc.wrapping_add(offset as u32)));
                } else if first & 0xF000 == 0xD000 && (first >> 8) & 0xF < 0xE {
                    let offset = sign_extend(u32::from(first & 0xFF) << 1, 9);
                    found.push((address, pc.wrapping_add(offset as u32)));
                }
                address += 2;
            }
        }
    }
    found
}

fn sign_extend(value: u32, bits: u32) -> i32 {
    ((value << (32 - bits)) as i32) >> (32 - bits)
}

/// The overlay's branches that would run code it does not hold once loaded: `branches` are
/// (from, to); `overlay` its bytes, `replaced` the section it is loaded over (starting at the
/// same address), `replaced_symbols` that section's symbols (address, name), sorted.
pub fn stray_branches(
    branches: &[(u32, u32)],
    overlay: Span,
    replaced: Span,
    replaced_symbols: &[(u32, String)],
) -> Vec<String> {
    let mut problems = Vec::new();
    for &(from, to) in branches {
        if !replaced.contains(to) {
            continue;
        }
        if !overlay.contains(to) {
            let name = replaced_symbols
                .iter()
                .rev()
                .find(|(at, _)| *at <= to)
                .map_or("", |(_, name)| name.as_str());
            problems.push(format!(
                "0x{from:08x} branches to 0x{to:08x} ({name}), past the overlay's end in {REPLACED}"
            ));
        } else if let Some((_, name)) = replaced_symbols
            .iter()
            .find(|(at, name)| *at == to && name.contains("Thunk_"))
        {
            problems.push(format!(
                "0x{from:08x} branches to 0x{to:08x} ({name}), which the overlay overwrites"
            ));
        }
    }
    problems
}

/// The branches of a kernel bank (`branches`, from its own bytes) that leave it: once the
/// other bank is loaded over it, nothing outside may be reached by a direct branch that
/// assumed this one, so its kernels must be leaves.
pub fn branches_out_of_bank(branches: &[(u32, u32)], bank: Span) -> Vec<String> {
    branches
        .iter()
        .filter(|(_, to)| !bank.contains(*to))
        .map(|(from, to)| format!("0x{from:08x} branches to 0x{to:08x}, outside its bank"))
        .collect()
}

/// The mapping symbols (`$a`, `$t`, `$d`) of `section`, sorted by address.
fn modes_of(file: &object::File, section: &object::Section) -> Vec<(u32, Mode)> {
    let mut modes: Vec<(u32, Mode)> = file
        .symbols()
        .filter(|symbol| symbol.section_index() == Some(section.index()))
        .filter_map(|symbol| {
            let mode = match symbol.name().unwrap_or("").split('.').next() {
                Some("$a") => Mode::Arm,
                Some("$t") => Mode::Thumb,
                Some("$d") => Mode::Data,
                _ => return None,
            };
            Some((symbol.address() as u32, mode))
        })
        .collect();
    modes.sort_by_key(|&(address, _)| address);
    modes
}

/// Checks that the kernel banks' code branches only within its own bank (see
/// [`branches_out_of_bank`]). A ROM without them passes.
fn check_kernel_banks(file: &object::File) -> Result<(), String> {
    for name in KERNEL_BANKS {
        let Some(bank) = file.section_by_name(name) else {
            continue;
        };
        let code = bank
            .data()
            .map_err(|error| format!("the bytes of {name}: {error}"))?;
        let span = Span {
            start: bank.address() as u32,
            end: (bank.address() + bank.size()) as u32,
        };
        let problems = branches_out_of_bank(&branches(code, span, &modes_of(file, &bank)), span);
        if !problems.is_empty() {
            return Err(format!(
                "the kernel bank {name} branches out of itself:\n  {}\nits kernels must be \
                 leaves: the other bank is loaded over it (linker.ld), and lld may place a \
                 thunk for the branch inside it.",
                problems.join("\n  ")
            ));
        }
    }
    Ok(())
}

/// Checks a linked ROM ELF (see the module's documentation), and that the kernel banks are
/// leaves. A ROM without the sections passes.
pub fn check(elf: &[u8]) -> Result<(), String> {
    let file = object::File::parse(elf).map_err(|error| format!("not an ELF: {error}"))?;
    check_kernel_banks(&file)?;
    let (Some(overlay), Some(replaced)) = (
        file.section_by_name(OVERLAY),
        file.section_by_name(REPLACED),
    ) else {
        return Ok(());
    };
    let code = overlay
        .data()
        .map_err(|error| format!("the overlay's bytes: {error}"))?;
    let mut modes = Vec::new();
    let mut replaced_symbols = Vec::new();
    for symbol in file.symbols() {
        let name = symbol.name().unwrap_or("");
        let section = symbol.section_index();
        let value = symbol.address() as u32;
        let mode = match name.split('.').next() {
            Some("$a") => Mode::Arm,
            Some("$t") => Mode::Thumb,
            Some("$d") => Mode::Data,
            _ => {
                if section == Some(replaced.index()) && !name.is_empty() {
                    replaced_symbols.push((value & !1, name.to_owned()));
                }
                continue;
            }
        };
        if section == Some(overlay.index()) {
            modes.push((value, mode));
        }
    }
    modes.sort_by_key(|&(address, _)| address);
    replaced_symbols.sort();
    let span = |section: &object::Section| Span {
        start: section.address() as u32,
        end: (section.address() + section.size()) as u32,
    };
    let (overlay_span, replaced_span) = (span(&overlay), span(&replaced));
    let problems = stray_branches(
        &branches(code, overlay_span, &modes),
        overlay_span,
        replaced_span,
        &replaced_symbols,
    );
    if problems.is_empty() {
        return Ok(());
    }
    Err(format!(
        "the math benchmark's overlay ({OVERLAY}) would run code of {REPLACED}, which it replaces \
         when the math scene loads it:\n  {}\nlld shares a thunk between every caller in range: \
         in linker.ld, move the renderer module that calls the same function from {REPLACED} to \
         .iwram, so that the thunk is made there (as render::planes is, for __aeabi_idiv).",
        problems.join("\n  ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ARM `BL` at `from` to `to`.
    fn arm_bl(from: u32, to: u32) -> [u8; 4] {
        (0xEB00_0000 | (to.wrapping_sub(from + 8) >> 2 & 0x00FF_FFFF)).to_le_bytes()
    }

    /// Thumb `BL` pair at `from` to `to`.
    fn thumb_bl(from: u32, to: u32) -> [u8; 4] {
        let offset = to.wrapping_sub(from + 4);
        let first = 0xF000 | (offset >> 12 & 0x7FF) as u16;
        let second = 0xF800 | (offset >> 1 & 0x7FF) as u16;
        let mut bytes = [0; 4];
        bytes[..2].copy_from_slice(&first.to_le_bytes());
        bytes[2..].copy_from_slice(&second.to_le_bytes());
        bytes
    }

    const AT: Span = Span {
        start: 0x0300_1000,
        end: 0x0300_1010,
    };

    #[test]
    fn decodes_arm_and_thumb_branches_and_skips_data() {
        let mut code = Vec::new();
        code.extend(arm_bl(0x0300_1000, 0x0300_0040)); // backwards, to .iwram
        code.extend(0xEAFF_FFFEu32.to_le_bytes()); // B . (a loop on itself)
        code.extend(thumb_bl(0x0300_1008, 0x0300_2000));
        code.extend(arm_bl(0, 0)); // in a literal pool: not a branch
        let modes = [
            (0x0300_1000, Mode::Arm),
            (0x0300_1008, Mode::Thumb),
            (0x0300_100C, Mode::Data),
        ];
        assert_eq!(
            branches(&code, AT, &modes),
            vec![
                (0x0300_1000, 0x0300_0040),
                (0x0300_1004, 0x0300_1004),
                (0x0300_1008, 0x0300_2000),
            ]
        );
        // Thumb B and B<cond>, forwards and backwards.
        let code = [0x02, 0xE0, 0xFC, 0xD1, 0x00, 0x00];
        let at = Span {
            start: 0x100,
            end: 0x106,
        };
        assert_eq!(
            branches(&code, at, &[(0x100, Mode::Thumb)]),
            vec![(0x100, 0x108), (0x102, 0xFE)]
        );
    }

    #[test]
    fn a_bank_may_branch_only_within_itself() {
        let bank = Span {
            start: 0x0300_4000,
            end: 0x0300_5000,
        };
        let inside = [(0x0300_4010, 0x0300_4000), (0x0300_4ffc, 0x0300_4ffc)];
        assert!(branches_out_of_bank(&inside, bank).is_empty());
        let out = [(0x0300_4010, 0x0300_5000), (0x0300_4020, 0x0800_0000)];
        assert_eq!(branches_out_of_bank(&out, bank).len(), 2);
    }

    #[test]
    fn refuses_branches_into_the_replaced_code_only() {
        let overlay = Span {
            start: 0x0300_4000,
            end: 0x0300_5000,
        };
        let replaced = Span {
            start: 0x0300_4000,
            end: 0x0300_6000,
        };
        let symbols = [
            (0x0300_4000, "draw_walls".to_string()),
            (
                0x0300_4800,
                "__ARMv4ABSLongBXThunk___aeabi_idiv".to_string(),
            ),
            (0x0300_5F00, "__ARMv4ABSLongBXThunk_panic".to_string()),
        ];
        let fine = [
            (0x0300_4100, 0x0300_4000), // inside the overlay, where the renderer had a function
            (0x0300_4100, 0x0300_1000), // .iwram
            (0x0300_4100, 0x0300_6010), // .bss: not code, but not the renderer's either
        ];
        assert!(stray_branches(&fine, overlay, replaced, &symbols).is_empty());
        let stray = [
            (0x0300_4100, 0x0300_4800), // a thunk under the overlay
            (0x0300_4104, 0x0300_5F04), // past the overlay, inside a thunk
        ];
        let problems = stray_branches(&stray, overlay, replaced, &symbols);
        assert_eq!(problems.len(), 2, "{problems:?}");
        assert!(problems[0].contains("aeabi_idiv") && problems[0].contains("overwrites"));
        assert!(problems[1].contains("Thunk_panic") && problems[1].contains("past the overlay"));
    }
}
