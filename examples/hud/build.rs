//! The game's maps and textures (`assets/`), compiled into OUT_DIR; a bad map stops the build
//! with its file, line and column.
fn main() -> Result<(), portalcast_assets::BuildError> {
    portalcast_assets::Builder::new("assets").build()?;
    Ok(())
}
