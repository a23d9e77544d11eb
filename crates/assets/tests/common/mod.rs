//! Helpers shared by the integration tests: scratch asset directories and simple images.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use image::{Rgba, RgbaImage};

/// A scratch directory under the system temp dir, removed on drop.
pub struct Scratch {
    pub dir: PathBuf,
}

impl Scratch {
    pub fn new(label: &str) -> Scratch {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "portalcast-assets-{}-{}-{label}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create scratch dir");
        Scratch { dir }
    }

    pub fn path(&self, relative: &str) -> PathBuf {
        self.dir.join(relative)
    }

    pub fn write(&self, relative: &str, bytes: &[u8]) -> PathBuf {
        let path = self.path(relative);
        std::fs::create_dir_all(path.parent().expect("has a parent")).expect("create folder");
        std::fs::write(&path, bytes).expect("write scratch file");
        path
    }

    /// Compiles the directory, which must fail, and returns its errors as
    /// `file:line:col: message` lines, the file relative to the directory.
    pub fn errors(&self) -> Vec<String> {
        let errors = portalcast_assets::compile_dir(&self.dir).expect_err("an error");
        errors
            .0
            .iter()
            .map(|error| {
                let file = error.path.strip_prefix(&self.dir).unwrap_or(&error.path);
                format!(
                    "{}:{}:{}: {}",
                    file.display(),
                    error.loc.line,
                    error.loc.col,
                    error.message
                )
            })
            .collect()
    }

    /// Compiles the directory, which must fail with exactly one error, and returns it as
    /// [`Scratch::errors`] does.
    pub fn only_error(&self) -> String {
        let found = self.errors();
        assert_eq!(found.len(), 1, "{found:#?}");
        found[0].clone()
    }

    pub fn png(&self, relative: &str, image: &RgbaImage) -> PathBuf {
        let path = self.path(relative);
        std::fs::create_dir_all(path.parent().expect("has a parent")).expect("create folder");
        image.save(&path).expect("write PNG");
        path
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// An opaque image with a simple two-colour pattern (so mips and layouts can be told apart).
pub fn pattern(width: u32, height: u32) -> RgbaImage {
    RgbaImage::from_fn(width, height, |x, y| {
        if (x / 4 + y / 4) % 2 == 0 {
            Rgba([200, 40, 40, 255])
        } else {
            Rgba([40, 40, 200, 255])
        }
    })
}

/// A one-room map: brick walls, stone floor and ceiling (or sky), a torch.
pub fn room_map(ceiling: &str) -> String {
    format!(
        "vertex a 0 0\nvertex b 128 0\nvertex c 128 128\nvertex d 0 128\n\
         sector room floor=0 ceil=96 floor_tex=stone ceil_tex={ceiling}\n\
         wall a b tex=brick\nwall b c tex=brick\nwall c d tex=brick\nwall d a tex=brick\n\
         player 64 64 angle=90\nthing torch 32 32\n"
    )
}

/// A scratch asset directory holding `room_map` and valid images for it.
pub fn valid_assets(label: &str, ceiling: &str) -> Scratch {
    let scratch = Scratch::new(label);
    scratch.write("maps/room.map", room_map(ceiling).as_bytes());
    scratch.png("textures/brick.png", &pattern(16, 16));
    scratch.png("textures/stone.png", &pattern(32, 32));
    scratch.png("sprites/torch.png", &sprite());
    scratch.png("sky/sky.png", &pattern(64, 16));
    scratch
}

/// A small sprite: a 6×10 opaque block in a transparent 8×12 frame.
pub fn sprite() -> RgbaImage {
    RgbaImage::from_fn(8, 12, |x, y| {
        if (1..7).contains(&x) && (1..11).contains(&y) {
            Rgba([230, 200, 40, 255])
        } else {
            Rgba([0, 0, 0, 0])
        }
    })
}

/// Path of the repository's shipped assets.
pub fn shipped_assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}
