//! The renderer in the ROM, under the real mGBA core, against the same renderer on the host
//! through the rasterizer twins: every shown frame's VRAM page must be identical, at every
//! resolution and lighting setting. Prints the ROM's cycles per frame.

mod common;

use common::*;
use portalcast::frame::{Resolution, PAGE_ROW_HALFWORDS};
use portalcast::raster::{HostCanvas, HostPage};
use portalcast::render::demo;
use portalcast::render::view::{Settings, View};
use portalcast::render::walk::Renderer;
use portalcast_harness::Keys;

#[test]
fn rom_frames_are_identical_to_the_host_renderer() {
    let mut emulator = boot();
    let assets = demo::render_assets();
    let mut renderer = Renderer::new();
    let mut compared = Vec::new();
    let mut maps_seen = std::collections::BTreeSet::new();
    // Each press comes after a few compared frames: Select for resolution, A for lighting.
    let presses = [
        Keys::NONE,
        Keys::SELECT,
        Keys::SELECT,
        Keys::A,
        Keys::SELECT,
        Keys::A,
        Keys::START,
        Keys::START,
        Keys::SELECT,
        Keys::START,
    ];
    for press in presses {
        // The ROM reads the keys once per rendered frame: hold a press for longer than one.
        emulator.set_keys(press);
        emulator
            .run_frames(if press == Keys::NONE { 1 } else { 90 })
            .unwrap_or_else(|error| panic!("{error}"));
        emulator.set_keys(Keys::NONE);
        emulator.drain_log();
        let mut checked_here = 0;
        // Frames take many VBlanks while the renderer is slower than its target: allow for it.
        for _ in 0..1500 {
            emulator
                .run_frame()
                .unwrap_or_else(|error| panic!("{error}"));
            let Some(line) = emulator
                .drain_log()
                .into_iter()
                .rev()
                .find(|line| line.is_debug_print() && line.text.starts_with("render "))
            else {
                continue;
            };
            let text = line.text;
            let frame = number(&text, "frame") as u32;
            let map_name = field(&text, "map").unwrap().to_owned();
            let map = demo::map_named(&map_name).expect("the ROM names a compiled map");
            let resolution = Resolution::from_label(field(&text, "res").unwrap()).unwrap();
            let lighting = demo::lighting_from_label(field(&text, "lighting").unwrap()).unwrap();
            let vram = read_page(&emulator, number(&text, "page") as u32);
            let mut page = HostPage::new();
            let view = View::new(
                &demo::camera_at(&map, frame),
                &Settings {
                    resolution,
                    lighting,
                    ..Settings::DEFAULT
                },
            );
            renderer.render(
                &map,
                &assets,
                &view,
                &mut HostCanvas {
                    page: &mut page,
                    resolution,
                },
            );
            let rows = resolution.height() * PAGE_ROW_HALFWORDS;
            let differing = vram.halfwords[..rows]
                .iter()
                .zip(&page.halfwords[..rows])
                .filter(|(a, b)| a != b)
                .count();
            if differing != 0 {
                let png =
                    screenshot_dir().join(format!("render-mismatch-{}.png", resolution.label()));
                emulator
                    .save_frame_png(&png)
                    .unwrap_or_else(|error| panic!("{error}"));
                panic!(
                    "{text}: {differing} halfwords differ from the host render (ROM frame in {})",
                    png.display()
                );
            }
            compared.push((resolution, lighting, number(&text, "cycles")));
            maps_seen.insert(map_name.clone());
            checked_here += 1;
            if checked_here == 2 {
                let png = screenshot_dir().join(format!(
                    "render-{map_name}-{}-{}.png",
                    resolution.label(),
                    demo::lighting_label(lighting)
                ));
                emulator
                    .save_frame_png(&png)
                    .unwrap_or_else(|error| panic!("{error}"));
                break;
            }
        }
        assert_eq!(
            checked_here, 2,
            "the ROM stopped printing render lines after {press}"
        );
    }
    let compiled: Vec<&str> = portalcast::assets::MAPS
        .iter()
        .map(|map| map.name)
        .collect();
    assert_eq!(
        maps_seen.iter().map(String::as_str).collect::<Vec<_>>(),
        compiled,
        "Start must reach every shipped map"
    );
    for resolution in Resolution::ALL {
        let cycles: Vec<u64> = compared
            .iter()
            .filter(|(r, ..)| *r == resolution)
            .map(|(.., c)| *c)
            .collect();
        assert!(!cycles.is_empty(), "{resolution:?} never compared");
        println!("{}: cycles per frame {:?}", resolution.label(), cycles);
    }
}
