//! A ROM's function symbols by address, for the profiler: which function an instruction address
//! belongs to.
//!
//! The linker script overlays two sections in IWRAM (linker.ld's `OVERLAY`): `.iwram_render`,
//! the renderer's hot code, and `.bench_iwram`, the math benchmark's loops, which the math scene
//! copies over it. Their symbols share addresses, so only one of the two may name them: the
//! renderer's by default (every scene but the math one runs it), the math benchmark's on request.

use std::path::Path;

use object::{Object, ObjectSection, ObjectSymbol, SymbolKind};

/// The linker script's section holding the math benchmark's IWRAM overlay.
pub const MATH_OVERLAY_SECTION: &str = ".bench_iwram";
/// The section it overlays: the renderer's IWRAM code.
pub const RENDER_OVERLAY_SECTION: &str = ".iwram_render";

/// Function symbols sorted by address, demangled without crate hashes.
pub struct FunctionSymbols {
    /// `(start, end, name)`, sorted by start.
    symbols: Vec<(u32, u32, String)>,
}

impl FunctionSymbols {
    /// The function symbols of the ELF at `elf`. Of the two sections sharing the IWRAM
    /// overlay's addresses, the math benchmark's names them with `math_overlay`, the renderer's
    /// otherwise.
    pub fn load(elf: &Path, math_overlay: bool) -> Result<FunctionSymbols, String> {
        let data = std::fs::read(elf)
            .map_err(|error| format!("{}: cannot read: {error}", elf.display()))?;
        let file = object::File::parse(&*data).map_err(|error| {
            format!(
                "{}: not an ELF ({error}); profile the ELF, the .gba has no symbols",
                elf.display()
            )
        })?;
        let hidden = if math_overlay {
            RENDER_OVERLAY_SECTION
        } else {
            MATH_OVERLAY_SECTION
        };
        let mut symbols: Vec<(u32, u32, String)> = file
            .symbols()
            .filter(|symbol| symbol.kind() == SymbolKind::Text && symbol.size() > 0)
            .filter(|symbol| {
                let section = symbol
                    .section_index()
                    .and_then(|index| file.section_by_index(index).ok())
                    .and_then(|section| section.name().ok().map(str::to_owned));
                section.as_deref() != Some(hidden)
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
