//! ROM, IWRAM and EWRAM sizes from the linked ELF's section headers and the `.gba` file.

use std::path::Path;

use object::{Object, ObjectSection};
use portalcast_xtask::{TaskError, TaskResult};

/// A memory region of the GBA's address map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// Its name in the report.
    pub name: &'static str,
    /// First address.
    pub start: u32,
    /// Bytes the program may use (IWRAM less the BIOS's top 256 bytes).
    pub usable: u32,
}

/// Internal work RAM: 32 KiB, of which the BIOS keeps the top 256 bytes (linker.ld).
pub const IWRAM: Region = Region {
    name: "IWRAM",
    start: 0x0300_0000,
    usable: 32 * 1024 - 256,
};
/// External work RAM: 256 KiB.
pub const EWRAM: Region = Region {
    name: "EWRAM",
    start: 0x0200_0000,
    usable: 256 * 1024,
};
/// Cartridge ROM: up to 32 MiB mapped.
pub const ROM: Region = Region {
    name: "ROM",
    start: 0x0800_0000,
    usable: 32 * 1024 * 1024,
};

/// Video RAM: 96 KiB, of which Mode 4's two bitmap pages and the OBJ tiles' colormap and column
/// windows leave some free for code (linker.ld's `vram*` regions).
pub const VRAM: Region = Region {
    name: "VRAM",
    start: 0x0600_0000,
    usable: 96 * 1024,
};

/// One allocated section of the ELF.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Section {
    /// Its name (`.iwram`, `.text`, `.bss`, …).
    pub name: String,
    /// Run-time address.
    pub address: u32,
    /// Bytes.
    pub size: u32,
    /// Whether it takes room in the `.gba` file too (not `NOBITS` like `.bss`).
    pub in_file: bool,
}

impl Section {
    /// Whether the section runs in `region` (the GBA's regions are told apart by the address's
    /// top byte).
    pub fn runs_in(&self, region: Region) -> bool {
        self.address >> 24 == region.start >> 24
    }
}

/// The sizes the report shows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Sizes {
    /// Bytes of the `.gba` file.
    pub rom_file: u64,
    /// The allocated sections, in header order.
    pub sections: Vec<Section>,
}

impl Sizes {
    /// Bytes used in `region`, from the lowest section start to the highest section end (so
    /// alignment gaps count, as they do at run time).
    pub fn used(&self, region: Region) -> u32 {
        let inside = self.sections.iter().filter(|s| s.runs_in(region));
        let start = inside.clone().map(|s| s.address).min();
        let end = inside.map(|s| s.address + s.size).max();
        match (start, end) {
            (Some(_), Some(end)) => end - region.start,
            _ => 0,
        }
    }
}

/// The `.gba` size and the ELF's allocated sections.
pub fn measure(elf: &Path, gba: &Path) -> TaskResult<Sizes> {
    let bytes =
        std::fs::read(elf).map_err(|error| TaskError(format!("{}: {error}", elf.display())))?;
    let rom_file = std::fs::metadata(gba)
        .map_err(|error| TaskError(format!("{}: {error}", gba.display())))?
        .len();
    let sections = allocated_sections(&bytes)
        .map_err(|problem| TaskError(format!("{}: {problem}", elf.display())))?;
    Ok(Sizes { rom_file, sections })
}

/// The allocated sections (`SHF_ALLOC`) of an ELF, with a size above 0, in header order.
pub fn allocated_sections(elf: &[u8]) -> Result<Vec<Section>, String> {
    let file = object::File::parse(elf).map_err(|error| format!("not an ELF: {error}"))?;
    let mut sections = Vec::new();
    for section in file.sections() {
        let object::SectionFlags::Elf { sh_flags } = section.flags() else {
            continue;
        };
        if sh_flags & u64::from(object::elf::SHF_ALLOC) == 0 || section.size() == 0 {
            continue;
        }
        sections.push(Section {
            name: section.name().unwrap_or("").to_owned(),
            address: section.address() as u32,
            size: section.size() as u32,
            in_file: section.kind() != object::SectionKind::UninitializedData,
        });
    }
    Ok(sections)
}

/// A memory region of linker.ld's `MEMORY` block.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LinkerRegion {
    /// Its name there (`vram`, `vram_after_pages`, …).
    pub name: String,
    /// `ORIGIN`.
    pub origin: u32,
    /// `LENGTH`.
    pub length: u32,
}

/// A linker script number: decimal or `0x` hexadecimal, with an optional `K` or `M`, or a
/// difference of two (`32K - 256`).
fn linker_number(text: &str) -> Option<u32> {
    if let Some((left, right)) = text.split_once(" - ") {
        return linker_number(left)?.checked_sub(linker_number(right)?);
    }
    let text = text.trim();
    let (digits, scale) = match text.as_bytes().last()? {
        b'K' => (&text[..text.len() - 1], 1024),
        b'M' => (&text[..text.len() - 1], 1024 * 1024),
        _ => (text, 1),
    };
    let value = match digits.strip_prefix("0x") {
        Some(hex) => u32::from_str_radix(hex, 16).ok()?,
        None => digits.parse().ok()?,
    };
    value.checked_mul(scale)
}

/// The regions of a linker script's `MEMORY` block (lines `name (attributes) : ORIGIN = …,
/// LENGTH = …`).
pub fn linker_regions(script: &str) -> Vec<LinkerRegion> {
    script
        .lines()
        .filter_map(|line| {
            let (head, values) = line.split_once(':')?;
            let name = head.split_whitespace().next()?;
            let origin = values.split_once("ORIGIN =")?.1.split(',').next()?;
            let length = values.split_once("LENGTH =")?.1;
            Some(LinkerRegion {
                name: name.to_string(),
                origin: linker_number(origin)?,
                length: linker_number(length)?,
            })
        })
        .collect()
}

/// The linker script's `STACK_RESERVE`, if it sets one.
pub fn stack_reserve(script: &str) -> Option<u32> {
    script.lines().find_map(|line| {
        let value = line.trim().strip_prefix("STACK_RESERVE =")?;
        linker_number(value.trim().trim_end_matches(';'))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regions_sum_from_their_start_to_the_last_section_end() {
        let section = |name: &str, address: u32, size: u32| Section {
            name: name.to_string(),
            address,
            size,
            in_file: true,
        };
        let sizes = Sizes {
            rom_file: 0,
            sections: vec![
                section(".text", 0x0800_0000, 100),
                section(".iwram", 0x0300_0000, 64),
                section(".bss", 0x0300_0040, 16),
                section(".ewram_bss", 0x0200_0000, 8),
            ],
        };
        assert_eq!(sizes.used(IWRAM), 80);
        assert_eq!(sizes.used(EWRAM), 8);
        assert_eq!(sizes.used(ROM), 100);
    }

    #[test]
    fn linker_regions_and_the_stack_reserve_are_read() {
        let script = "STACK_RESERVE = 4K;\nMEMORY {\n  iwram (w!x) : ORIGIN = 0x03000000, LENGTH = 32K - 256\n  vram  (rwx) : ORIGIN = 0x06016E60, LENGTH = 0x11A0\n}\n";
        assert_eq!(stack_reserve(script), Some(4096));
        let regions = linker_regions(script);
        assert_eq!(regions.len(), 2);
        assert_eq!(regions[0].length, 32 * 1024 - 256);
        assert_eq!(
            regions[1],
            LinkerRegion {
                name: "vram".to_string(),
                origin: 0x0601_6E60,
                length: 0x11A0
            }
        );
    }

    #[test]
    fn a_non_elf_is_refused() {
        assert!(allocated_sections(b"not an elf").is_err());
    }
}
