//! The GBA memory the compiled assets may take at run time, shared by the asset compiler (which
//! decides what fits) and the engine (which asserts that its own state leaves that room).

/// EWRAM, the GBA's 256 KiB of slower work RAM.
pub const EWRAM_BYTES: usize = 256 * 1024;

/// The most EWRAM the engine keeps for its own state (the renderer's memory, and live state to
/// come): the engine asserts at compile time that its EWRAM statics fit, and the asset compiler
/// gives textures only what is left. 72 KiB since the things stage (its sprites' clip windows
/// and the portal middles' columns, about 13 KiB) joined the renderer; 82 KiB since the walk
/// follows 256 portals in a row instead of 64 (Doom maps, issue 19: 44 bytes a level).
pub const EWRAM_ENGINE_BYTES: usize = 82 * 1024;

/// Bytes the engine's EWRAM table of textures takes per texture (a [`crate::Texture`] on the
/// GBA, asserted there), re-pointed at the copied texels.
pub const TEXTURE_ENTRY_BYTES: usize = 32;

/// Bytes of EWRAM the texels of `texture_count` textures may take: what the engine's own state
/// and the texture table leave. The compiler copies the hottest textures that fit into it and
/// leaves the rest in the cartridge.
pub const fn ewram_texel_budget(texture_count: usize) -> usize {
    EWRAM_BYTES.saturating_sub(EWRAM_ENGINE_BYTES + texture_count * TEXTURE_ENTRY_BYTES)
}
