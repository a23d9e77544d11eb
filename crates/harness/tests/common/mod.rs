//! Tiny GBA programs built from raw bytes, so that the harness tests run the real mGBA core
//! without depending on an ARM toolchain or on the portalcast ROM.
//!
//! `Asm` hand-encodes the handful of ARM (32-bit) instructions the tests need; each encoder
//! documents its bit layout (ARM Architecture Reference Manual, ARMv4T). Code runs from ROM at
//! 0x080000C0, right after the cartridge header; constants live in a literal pool after the code.

#![allow(dead_code)] // each test file uses a different subset

use std::path::{Path, PathBuf};

/// Where the cartridge is mapped, and where the code starts (after the 0xC0-byte header).
pub const ROM_BASE: u32 = 0x0800_0000;
pub const CODE_BASE: u32 = ROM_BASE + 0xC0;

/// mGBA's debug output registers.
pub const DEBUG_STRING: u32 = 0x04FF_F600;
pub const DEBUG_FLAGS: u32 = 0x04FF_F700;
pub const DEBUG_ENABLE: u32 = 0x04FF_F780;
/// Bit 8 of DEBUG_FLAGS sends the string; bits 0-2 are the level (0 fatal .. 4 debug).
pub const DEBUG_SEND: u16 = 0x100;
pub const LEVEL_FATAL: u16 = 0;
pub const LEVEL_ERROR: u16 = 1;
pub const LEVEL_INFO: u16 = 3;

pub const DISPCNT: u32 = 0x0400_0000;
pub const KEYINPUT: u32 = 0x0400_0130;
pub const VRAM: u32 = 0x0600_0000;
pub const EWRAM: u32 = 0x0200_0000;

const COND_AL: u32 = 0xE << 28;
const COND_NE: u32 = 0x1 << 28;

/// A minimal ARM assembler: instructions, plus `LDR rd, =constant` through a literal pool.
#[derive(Default)]
pub struct Asm {
    words: Vec<u32>,
    literals: Vec<u32>,
    /// (instruction index, literal index) pairs whose PC-relative offset is filled in `finish`.
    literal_loads: Vec<(usize, usize)>,
}

impl Asm {
    pub fn new() -> Asm {
        Asm::default()
    }

    /// Address of the next instruction.
    pub fn here(&self) -> u32 {
        CODE_BASE + 4 * self.words.len() as u32
    }

    /// `LDR rd, [pc, #offset]` loading `value` from the pool.
    /// Encoding: cond 01 I=0 P=1 U=1 B=0 W=0 L=1 | Rn=15 | Rd | imm12 = 0xE59F_0000 | Rd<<12 | off,
    /// where off = pool address - (this instruction + 8), the ARM pipeline's view of PC.
    pub fn ldr_const(&mut self, rd: u32, value: u32) {
        let literal = match self.literals.iter().position(|&known| known == value) {
            Some(index) => index,
            None => {
                self.literals.push(value);
                self.literals.len() - 1
            }
        };
        self.literal_loads.push((self.words.len(), literal));
        self.words.push(COND_AL | 0x059F_0000 | rd << 12);
    }

    /// `STR rd, [rn]`: cond 01 I=0 P=1 U=1 B=0 W=0 L=0 | Rn | Rd | imm12=0 = 0xE580_0000.
    pub fn str_word(&mut self, rd: u32, rn: u32) {
        self.words.push(COND_AL | 0x0580_0000 | rn << 16 | rd << 12);
    }

    /// `STRH rd, [rn]`: cond 000 P=1 U=1 I=1 W=0 L=0 | Rn | Rd | 0000 1011 0000 = 0xE1C0_00B0.
    pub fn strh(&mut self, rd: u32, rn: u32) {
        self.words.push(COND_AL | 0x01C0_00B0 | rn << 16 | rd << 12);
    }

    /// `LDRH rd, [rn]`: as STRH with L=1 (bit 20) = 0xE1D0_00B0.
    pub fn ldrh(&mut self, rd: u32, rn: u32) {
        self.words.push(COND_AL | 0x01D0_00B0 | rn << 16 | rd << 12);
    }

    /// `MOV rd, #imm8`: cond 00 I=1 opcode=1101 S=0 | Rn=0 | Rd | rotate=0 imm8 = 0xE3A0_0000.
    pub fn mov_imm(&mut self, rd: u32, imm8: u8) {
        self.words
            .push(COND_AL | 0x03A0_0000 | rd << 12 | u32::from(imm8));
    }

    /// `SUBS rd, rn, #imm8`: cond 00 I=1 opcode=0010 S=1 | Rn | Rd | imm8 = 0xE250_0000.
    pub fn subs_imm(&mut self, rd: u32, rn: u32, imm8: u8) {
        self.words
            .push(COND_AL | 0x0250_0000 | rn << 16 | rd << 12 | u32::from(imm8));
    }

    /// `MOV pc, rm` (a jump to the address in rm): cond 00 I=0 opcode=1101 S=0 | Rn=0 | Rd=15 |
    /// shift=0 | Rm = 0xE1A0_F000.
    pub fn mov_pc(&mut self, rm: u32) {
        self.words.push(COND_AL | 0x01A0_F000 | rm);
    }

    /// `TST rn, #imm8`: cond 00 I=1 opcode=1000 S=1 | Rn | Rd=0 | imm8 = 0xE310_0000.
    pub fn tst_imm(&mut self, rn: u32, imm8: u8) {
        self.words
            .push(COND_AL | 0x0310_0000 | rn << 16 | u32::from(imm8));
    }

    /// `B target`: cond 1010 | signed word offset from this instruction + 8, 24 bits.
    pub fn b(&mut self, target: u32) {
        self.branch(COND_AL, target);
    }

    /// `BNE target`: as B with cond NE (0001).
    pub fn bne(&mut self, target: u32) {
        self.branch(COND_NE, target);
    }

    fn branch(&mut self, cond: u32, target: u32) {
        let offset = (target as i64 - (self.here() as i64 + 8)) / 4;
        self.words
            .push(cond | 0x0A00_0000 | (offset as u32 & 0x00FF_FFFF));
    }

    /// `*(u32*)address = value` (clobbers r0, r1).
    pub fn store32(&mut self, address: u32, value: u32) {
        self.ldr_const(0, address);
        self.ldr_const(1, value);
        self.str_word(1, 0);
    }

    /// `*(u16*)address = value` (clobbers r0, r1).
    pub fn store16(&mut self, address: u32, value: u16) {
        self.ldr_const(0, address);
        self.ldr_const(1, u32::from(value));
        self.strh(1, 0);
    }

    /// Prints `text` on mGBA's debug output at `level` (clobbers r0, r1), as a ROM would.
    pub fn debug_print(&mut self, text: &str, level: u16) {
        assert!(text.len() < 0x100, "mGBA's debug string holds 255 bytes");
        self.store16(DEBUG_ENABLE, 0xC0DE);
        for (index, chunk) in text.as_bytes().chunks(4).enumerate() {
            let mut word = [0u8; 4];
            word[..chunk.len()].copy_from_slice(chunk);
            self.store32(DEBUG_STRING + 4 * index as u32, u32::from_le_bytes(word));
        }
        self.store16(DEBUG_FLAGS, DEBUG_SEND | level);
    }

    /// `b .`: spin forever (the program's end).
    pub fn halt(&mut self) {
        let here = self.here();
        self.b(here);
    }

    /// Code followed by the literal pool, as bytes for address CODE_BASE.
    pub fn finish(mut self) -> Vec<u8> {
        let pool_base = CODE_BASE + 4 * self.words.len() as u32;
        for &(instruction, literal) in &self.literal_loads {
            let instruction_address = CODE_BASE + 4 * instruction as u32;
            let literal_address = pool_base + 4 * literal as u32;
            let offset = literal_address - (instruction_address + 8);
            assert!(offset < 4096, "literal pool out of LDR reach");
            self.words[instruction] |= offset;
        }
        self.words
            .iter()
            .chain(&self.literals)
            .flat_map(|word| word.to_le_bytes())
            .collect()
    }
}

/// A cartridge image: a valid header (entry branch, fixed byte 0x96, complement check) + code.
/// The Nintendo logo stays zero: mGBA's HLE BIOS does not check it.
pub fn gba_rom(code: &[u8]) -> Vec<u8> {
    let mut rom = vec![0u8; 0xC0];
    // Entry: `B 0x080000C0` from 0x08000000: offset (0xC0 - 8) / 4 = 0x2E.
    rom[0..4].copy_from_slice(&0xEA00_002Eu32.to_le_bytes());
    rom[0xA0..0xAC].copy_from_slice(b"PCHARNESS\0\0\0");
    rom[0xAC..0xB0].copy_from_slice(b"PCHT");
    rom[0xB0..0xB2].copy_from_slice(b"00");
    rom[0xB2] = 0x96;
    let sum = rom[0xA0..=0xBC]
        .iter()
        .fold(0u8, |sum, &byte| sum.wrapping_sub(byte));
    rom[0xBD] = sum.wrapping_sub(0x19);
    rom.extend_from_slice(code);
    rom
}

/// The same program as a 32-bit little-endian ARM ELF with one loadable segment at 0x08000000,
/// like a linker would produce (minus sections, which mGBA does not need).
pub fn gba_elf(rom: &[u8]) -> Vec<u8> {
    const EHDR: usize = 52;
    const PHDR: usize = 32;
    const DATA_OFFSET: usize = 0x100;
    let mut elf = vec![0u8; DATA_OFFSET];
    elf[0..4].copy_from_slice(b"\x7fELF");
    elf[4] = 1; // ELFCLASS32
    elf[5] = 1; // ELFDATA2LSB
    elf[6] = 1; // EV_CURRENT
    let put16 = |elf: &mut Vec<u8>, at: usize, value: u16| {
        elf[at..at + 2].copy_from_slice(&value.to_le_bytes())
    };
    let put32 = |elf: &mut Vec<u8>, at: usize, value: u32| {
        elf[at..at + 4].copy_from_slice(&value.to_le_bytes())
    };
    put16(&mut elf, 0x10, 2); // ET_EXEC
    put16(&mut elf, 0x12, 40); // EM_ARM
    put32(&mut elf, 0x14, 1); // e_version
    put32(&mut elf, 0x18, ROM_BASE); // e_entry
    put32(&mut elf, 0x1C, EHDR as u32); // e_phoff
    put32(&mut elf, 0x24, 0x0500_0000); // e_flags: EABI version 5
    put16(&mut elf, 0x28, EHDR as u16); // e_ehsize
    put16(&mut elf, 0x2A, PHDR as u16); // e_phentsize
    put16(&mut elf, 0x2C, 1); // e_phnum
    put16(&mut elf, 0x2E, 40); // e_shentsize (no sections)
    let ph = EHDR;
    put32(&mut elf, ph, 1); // PT_LOAD
    put32(&mut elf, ph + 4, DATA_OFFSET as u32); // p_offset
    put32(&mut elf, ph + 8, ROM_BASE); // p_vaddr
    put32(&mut elf, ph + 12, ROM_BASE); // p_paddr
    put32(&mut elf, ph + 16, rom.len() as u32); // p_filesz
    put32(&mut elf, ph + 20, rom.len() as u32); // p_memsz
    put32(&mut elf, ph + 24, 5); // PF_R | PF_X
    put32(&mut elf, ph + 28, 4); // p_align
    elf.extend_from_slice(rom);
    elf
}

/// A scratch directory unique to one test, removed on drop.
pub struct Scratch {
    dir: PathBuf,
}

impl Scratch {
    pub fn new(name: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!(
            "portalcast-harness-{}-{}",
            name,
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create scratch directory");
        Scratch { dir }
    }

    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// Writes `bytes` to `name` inside the scratch directory and returns its path.
    pub fn write(&self, name: &str, bytes: &[u8]) -> PathBuf {
        let path = self.dir.join(name);
        std::fs::write(&path, bytes).expect("write scratch file");
        path
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Writes a ROM whose code is `build`'s program and returns its path.
pub fn write_rom(scratch: &Scratch, name: &str, build: impl FnOnce(&mut Asm)) -> PathBuf {
    let mut asm = Asm::new();
    build(&mut asm);
    scratch.write(name, &gba_rom(&asm.finish()))
}
