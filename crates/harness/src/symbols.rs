//! A ROM's function symbols by address, for the profiler: which function an instruction address
//! belongs to.
//!
//! The linker script overlays sections in IWRAM (linker.ld's `OVERLAY`s): `.iwram_render`, the
//! renderer's hot code, and `.bench_iwram`, the math benchmark's loops, which the math scene
//! copies over it; the two span kernel banks, `.iwram_kernels_lit` and `.iwram_kernels_unlit`,
//! whichever of which the frame's lighting needs is copied in; and the four column kernel
//! banks, `.iwram_columns_{dbl,pair}_{lit,unlit}`, by lighting and by the resolution's packing.
//! Symbols of sections that share addresses would name each other's code, so only one of each
//! set names them: the renderer's by default (every scene but the math one runs it), the math
//! benchmark's on request; the lit kernels by default (the default lighting lights), the unlit
//! ones on request; the doubled column kernels by default (120 wide), the pair ones (240 wide)
//! on request.

use std::path::Path;

use object::{Object, ObjectSection, ObjectSymbol, SymbolKind};

/// The linker script's section holding the math benchmark's IWRAM overlay.
pub const MATH_OVERLAY_SECTION: &str = ".bench_iwram";
/// The section it overlays: the renderer's IWRAM code.
pub const RENDER_OVERLAY_SECTION: &str = ".iwram_render";
/// The kernel banks, which share their addresses.
pub const LIT_KERNELS_SECTION: &str = ".iwram_kernels_lit";
/// See [`LIT_KERNELS_SECTION`].
pub const UNLIT_KERNELS_SECTION: &str = ".iwram_kernels_unlit";
/// The column kernel banks, which share their addresses: by packing (doubled, pair), then by
/// lighting (lit, unlit).
pub const COLUMN_KERNEL_SECTIONS: [[&str; 2]; 2] = [
    [".iwram_columns_dbl_lit", ".iwram_columns_dbl_unlit"],
    [".iwram_columns_pair_lit", ".iwram_columns_pair_unlit"],
];

/// Which of the sections that share addresses name them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Overlays {
    /// The math benchmark's overlay instead of the renderer's code.
    pub math: bool,
    /// The unlit kernel banks instead of the lit ones.
    pub unlit_kernels: bool,
    /// The column kernels of 240-wide frames (pairs of columns) instead of 120-wide ones.
    pub pair_kernels: bool,
}

/// Function symbols sorted by address, demangled without crate hashes.
pub struct FunctionSymbols {
    /// `(start, end, name)`, sorted by start.
    symbols: Vec<(u32, u32, String)>,
}

impl FunctionSymbols {
    /// The function symbols of the ELF at `elf`, of the sections `overlays` picks among those
    /// that share addresses.
    pub fn load(elf: &Path, overlays: Overlays) -> Result<FunctionSymbols, String> {
        let data = std::fs::read(elf)
            .map_err(|error| format!("{}: cannot read: {error}", elf.display()))?;
        let file = object::File::parse(&*data).map_err(|error| {
            format!(
                "{}: not an ELF ({error}); profile the ELF, the .gba has no symbols",
                elf.display()
            )
        })?;
        let shown_columns = COLUMN_KERNEL_SECTIONS[usize::from(overlays.pair_kernels)]
            [usize::from(overlays.unlit_kernels)];
        let mut hidden: Vec<&str> = COLUMN_KERNEL_SECTIONS
            .iter()
            .flatten()
            .copied()
            .filter(|name| *name != shown_columns)
            .collect();
        hidden.push(if overlays.math {
            RENDER_OVERLAY_SECTION
        } else {
            MATH_OVERLAY_SECTION
        });
        hidden.push(if overlays.unlit_kernels {
            LIT_KERNELS_SECTION
        } else {
            UNLIT_KERNELS_SECTION
        });
        let mut symbols: Vec<(u32, u32, String)> = file
            .symbols()
            .filter(|symbol| symbol.kind() == SymbolKind::Text && symbol.size() > 0)
            .filter(|symbol| {
                let section = symbol
                    .section_index()
                    .and_then(|index| file.section_by_index(index).ok())
                    .and_then(|section| section.name().ok().map(str::to_owned));
                !section.is_some_and(|name| hidden.contains(&name.as_str()))
            })
            .filter_map(|symbol| {
                let start = (symbol.address() as u32) & !1;
                let name = symbol.name().ok()?;
                Some((
                    start,
                    start + symbol.size() as u32,
                    format!("{:#}", rustc_demangle::demangle(name)),
                ))
            })
            .collect();
        if symbols.is_empty() {
            return Err(format!(
                "{}: no function symbols (stripped?)",
                elf.display()
            ));
        }
        symbols.sort();
        Ok(FunctionSymbols { symbols })
    }

    /// The function `address` is in, if any.
    pub fn lookup(&self, address: u32) -> Option<&str> {
        let address = address & !1;
        let index = self
            .symbols
            .partition_point(|(start, _, _)| *start <= address);
        let (start, end, name) = self.symbols.get(index.checked_sub(1)?)?;
        (address >= *start && address < *end).then_some(name.as_str())
    }

    /// Every function, as `(start, end, name)` in address order.
    pub fn all(&self) -> &[(u32, u32, String)] {
        &self.symbols
    }
}
