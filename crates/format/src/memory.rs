//! The GBA memory the compiled assets may take at run time, shared by the asset compiler (which
//! decides what fits) and the engine (which asserts that its own state leaves that room).

/// EWRAM, the GBA's 256 KiB of slower work RAM.
pub const EWRAM_BYTES: usize = 256 * 1024;

/// The most EWRAM the engine keeps for its own state (the renderer's memory, the game's and the
/// bench scene's, but for the live map state, [`live_state_bytes`]): the engine asserts at compile time that its EWRAM statics fit, and the asset compiler
/// gives textures only what is left. 72 KiB since the things stage (its sprites' clip windows
/// and the portal middles' columns, about 13 KiB) joined the renderer; 82 KiB since the walk
/// follows 256 portals in a row instead of 64 (Doom maps, issue 19: 44 bytes a level); 86 KiB
/// since the portal middles keep two full-width layers of columns (Doom's cages of bars). Room
/// over room's four full-width planes of windows waiting (1.9 KiB, issue 20) fit in it.
pub const EWRAM_ENGINE_BYTES: usize = 86 * 1024;

/// Bytes each of the engine's EWRAM tables of textures ([`TEXTURE_TABLES`]) takes per texture
/// (a [`crate::Texture`] on the GBA, asserted there).
pub const TEXTURE_ENTRY_BYTES: usize = 32;

/// Bytes the game's live state takes per sector (a [`crate::Sector`] and its touch door,
/// asserted by the engine).
pub const LIVE_SECTOR_BYTES: usize = 22;
/// Bytes one mover's live state takes (the engine's `MoverState` and its touch box, asserted
/// by the engine).
pub const LIVE_MOVER_BYTES: usize = 24;
/// Bytes the game's live copy of one trigger takes (a [`crate::Trigger`], asserted on the GBA).
pub const LIVE_TRIGGER_BYTES: usize = 8;

/// Copies of the live map state the engine keeps in EWRAM: the game's and the bench scene's
/// (its fly-through's doors and lifts).
pub const LIVE_STATE_COPIES: usize = 2;
/// Tables of textures the engine keeps in EWRAM ([`TEXTURE_ENTRY_BYTES`] a texture each): the
/// one re-pointed at the EWRAM copy and the one a scene borrows.
pub const TEXTURE_TABLES: usize = 2;

/// Bytes of EWRAM the live map state takes beyond [`EWRAM_ENGINE_BYTES`], all its
/// [`LIVE_STATE_COPIES`]: room for `sectors` sectors, `movers` movers' states and `triggers`
/// triggers in each (the most of the ROM's maps: a Doom map's 434 pieces with 12 doors take
/// 9.6 KiB a copy).
pub const fn live_state_bytes(sectors: usize, movers: usize, triggers: usize) -> usize {
    LIVE_STATE_COPIES
        * (sectors * LIVE_SECTOR_BYTES + movers * LIVE_MOVER_BYTES + triggers * LIVE_TRIGGER_BYTES)
}

/// Bytes of EWRAM the texels of `texture_count` textures may take: what the engine's own state,
/// the game's live map state (`live_state`, [`live_state_bytes`]) and the texture table leave.
/// The compiler copies the hottest textures that fit into it and leaves the rest in the
/// cartridge.
pub const fn ewram_texel_budget(texture_count: usize, live_state: usize) -> usize {
    EWRAM_BYTES.saturating_sub(
        EWRAM_ENGINE_BYTES + live_state + texture_count * TEXTURE_TABLES * TEXTURE_ENTRY_BYTES,
    )
}
