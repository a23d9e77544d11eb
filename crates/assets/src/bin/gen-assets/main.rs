//! Draws the shipped assets: textures, the sky panorama, the sprites (torch, pillar, lamp, the
//! animated brazier flame as a strip, the statue in eight rotations, and the portal middles:
//! an iron grate and a leaded-glass window), and the benchmark map. Deterministic (fixed seeds), so re-running it reproduces the committed files.
//!
//! Usage: `cargo run -p portalcast-assets --bin gen-assets -- assets/`

mod bench_map;
mod paint;
mod sets;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn write_png(path: &Path, image: &impl Fn(&Path) -> image::ImageResult<()>) -> Result<(), String> {
    image(path).map_err(|e| format!("{}: cannot write ({e})", path.display()))
}

fn run(dir: &Path) -> Result<(), String> {
    let folder = |name: &str| -> Result<PathBuf, String> {
        let path = dir.join(name);
        std::fs::create_dir_all(&path)
            .map_err(|e| format!("{}: cannot create ({e})", path.display()))?;
        Ok(path)
    };
    let textures = folder(portalcast_assets::TEXTURES_DIR)?;
    for (name, image) in paint::textures() {
        write_png(&textures.join(format!("{name}.png")), &|p| image.save(p))?;
    }
    let sky = paint::sky();
    write_png(
        &folder(portalcast_assets::SKY_DIR)?.join(portalcast_assets::SKY_FILE),
        &|p| sky.save(p),
    )?;
    let sprites = folder(portalcast_assets::SPRITES_DIR)?;
    let mut sprite_images = vec![
        ("torch".to_string(), paint::torch()),
        ("pillar".to_string(), paint::pillar()),
        ("lamp".to_string(), paint::lamp()),
        ("grate".to_string(), paint::grate()),
        ("window".to_string(), paint::window()),
        (
            format!("flame.strip{}", sets::FLAME_FRAMES),
            sets::flame_strip(),
        ),
    ];
    for rotation in 0..sets::STATUE_ROTATIONS {
        sprite_images.push((format!("statue.r{rotation}"), sets::statue(rotation)));
    }
    for (name, image) in &sprite_images {
        write_png(&sprites.join(format!("{name}.png")), &|p| image.save(p))?;
    }
    let (text, (sectors, walls, portals)) = bench_map::bench_map();
    let map = folder(portalcast_assets::MAPS_DIR)?.join("bench.map");
    std::fs::write(&map, text).map_err(|e| format!("{}: cannot write ({e})", map.display()))?;
    println!(
        "wrote {} textures, the sky, {} sprite files and bench.map ({sectors} sectors, {walls} walls, {portals} portal sides) into {}",
        paint::textures().len(),
        sprite_images.len(),
        dir.display()
    );
    Ok(())
}

fn main() -> ExitCode {
    let mut args = std::env::args_os().skip(1);
    let (Some(dir), None) = (args.next(), args.next()) else {
        eprintln!("usage: gen-assets ASSET_DIR   (e.g. cargo run -p portalcast-assets --bin gen-assets -- assets/)");
        return ExitCode::FAILURE;
    };
    match run(Path::new(&dir)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("{message}");
            ExitCode::FAILURE
        }
    }
}
