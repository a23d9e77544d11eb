//! The renderer in the ROM, under the real mGBA core, against the same renderer on the host
//! through the rasterizer twins: every compared frame's VRAM page must be identical, on every
//! shipped map, at every resolution and lighting setting, with the Start menu drawn over the
//! view too. The host renders the pose the ROM logged (its `player` line) with the settings of
//! its `render` line. Key presses drive the ROM: the menu switches the settings, the d-pad
//! moves the player so the poses vary. Prints the ROM's cycles per frame. Every value of every
//! knob is compared, half-width floors at 240×160 among them.

mod common;

use common::demos::{render_line_settings, PlayerLine, WorldLine, WorldLines};
use common::*;
use portalcast::frame::{Resolution, PAGE_ROW_HALFWORDS};
use portalcast::raster::{HostCanvas, HostPage};
use portalcast::render::view::{
    Floors, Preprocessing, Settings, TexturePlacement, ThingsShown, View,
};
use portalcast::render::walk::Renderer;
use portalcast::render::RenderAssets;
use portalcast_harness::{Emulator, Keys};
use portalcast_rom::demo;
use portalcast_rom::menu::{self, MenuColours, Shown};
use std::collections::BTreeSet;

/// One frame the ROM drew, compared.
struct Compared {
    map: String,
    resolution: Resolution,
    lighting: portalcast::render::light::Lighting,
    textures: TexturePlacement,
    preprocessing: Preprocessing,
    floors: Floors,
    hud: bool,
    menu: bool,
    cycles: u64,
    things_drawn: u32,
    middles_drawn: u32,
    translucent_drawn: u32,
    things: ThingsShown,
}

/// Runs the ROM frame by frame and compares each frame it draws with the host's render.
struct Checker {
    emulator: Emulator,
    assets: RenderAssets<'static>,
    renderer: Renderer,
    colours: MenuColours,
    player: Option<PlayerLine>,
    /// The live world of the frame the `player` line describes (its `world …` line), on a map
    /// with movers or light effects.
    world: Option<WorldLine>,
    /// The parts of the frame's `world` lines so far.
    world_lines: WorldLines,
    compared: Vec<Compared>,
    screenshots: BTreeSet<String>,
}

impl Checker {
    /// Runs one emulator frame with `keys` held; compares the frame the ROM drew in it, if any.
    fn step(&mut self, keys: Keys) -> Option<&Compared> {
        self.emulator.set_keys(keys);
        self.emulator
            .run_frame()
            .unwrap_or_else(|error| panic!("{error}"));
        let mut drawn = false;
        for line in self.emulator.drain_log() {
            if !line.is_debug_print() {
                continue;
            }
            // In log order: a frame's `render` line pairs with the `player` line before it
            // (the next frame's `player` line may follow in the same emulator frame).
            if line.text.starts_with("player ") {
                self.player = Some(PlayerLine::parse(&line.text));
                self.world = None;
            } else if line.text.starts_with("world ") {
                if let Some(whole) = self.world_lines.push(&line.text) {
                    self.world = Some(whole);
                }
            } else if line.text.starts_with("render ") {
                self.compare(&line.text);
                drawn = true;
            }
        }
        if drawn {
            self.compared.last()
        } else {
            None
        }
    }

    fn compare(&mut self, text: &str) {
        let player = self
            .player
            .clone()
            .expect("a player line precedes every frame");
        assert_eq!(player.frame, number(text, "frame") as u32, "{text}");
        let map_name = field(text, "map").unwrap().to_owned();
        let (map, settings) = render_line_settings(text);
        let Settings {
            resolution,
            lighting,
            textures,
            preprocessing,
            floors,
            things,
            slope_steps: _,
        } = settings;
        let camera = player.camera();
        let mut page = HostPage::new();
        let mut canvas = HostCanvas {
            page: &mut page,
            resolution,
            halved_flats: false,
        };
        // The map as the ROM's game had it: the live world the ROM logged.
        let world = WorldLine::world_of(self.world.as_ref(), &map);
        let live = world.map(&map);
        let stats = self.renderer.render(
            &live,
            &self.assets,
            &View::new(&camera, &settings).at_tick(player.tick),
            &mut canvas,
        );
        if player.hud {
            let cycles = number(text, "cycles") as u32;
            menu::draw_hud(&mut canvas, &menu::hud_line(cycles), self.colours);
        }
        let menu_open = player.menu >= 0;
        if menu_open {
            let shown = Shown {
                resolution,
                lighting,
                map: map.name,
                fly: player.fly,
                run: player.run,
                hud: player.hud,
                textures,
                preprocessing,
                floors,
                things,
            };
            menu::draw(
                &mut canvas,
                &menu::text(player.menu as usize, &shown),
                self.colours,
            );
        }
        let vram = read_page(&self.emulator, number(text, "page") as u32);
        let rows = resolution.height() * PAGE_ROW_HALFWORDS;
        let differing = vram.halfwords[..rows]
            .iter()
            .zip(&page.halfwords[..rows])
            .filter(|(a, b)| a != b)
            .count();
        if differing != 0 {
            let png = screenshot_dir().join(format!("render-mismatch-{}.png", resolution.label()));
            self.emulator
                .save_frame_png(&png)
                .unwrap_or_else(|error| panic!("{error}"));
            panic!(
                "{text}\n{}: {differing} halfwords differ from the host render (ROM frame in {})",
                player.text,
                png.display()
            );
        }
        // The second frame of each setting (the first may still show the previous page).
        let name = if menu_open {
            format!("menu-{map_name}-{}", resolution.label())
        } else {
            format!(
                "render-{map_name}-{}-{}",
                resolution.label(),
                demo::lighting_label(lighting)
            )
        };
        let seen_before = self
            .compared
            .iter()
            .any(|c| c.map == map_name && c.resolution == resolution && c.lighting == lighting);
        if seen_before && self.screenshots.insert(name.clone()) {
            self.emulator
                .save_frame_png(&screenshot_dir().join(format!("{name}.png")))
                .unwrap_or_else(|error| panic!("{error}"));
        }
        self.compared.push(Compared {
            map: map_name,
            resolution,
            lighting,
            textures,
            preprocessing,
            floors,
            hud: player.hud,
            menu: menu_open,
            cycles: number(text, "cycles"),
            things_drawn: stats.things_drawn,
            middles_drawn: stats.middles_drawn,
            translucent_drawn: stats.translucent_drawn,
            things,
        });
    }

    /// Presses `key` (held for 3 frames, then 3 frames of nothing: the game reads every VBlank,
    /// so one would do).
    fn press(&mut self, key: Keys) {
        for _ in 0..3 {
            self.step(key);
        }
        for _ in 0..3 {
            self.step(Keys::NONE);
        }
    }

    /// Holds `keys` until `count` more frames with the menu `menu_open` are compared.
    fn hold_until_compared(&mut self, keys: Keys, count: usize, menu_open: bool) {
        let mut matched = 0;
        // Frames take many VBlanks while the renderer is slower than its target.
        for _ in 0..1500 {
            if self.step(keys).is_some_and(|c| c.menu == menu_open) {
                matched += 1;
                if matched == count {
                    return;
                }
            }
        }
        panic!("the ROM stopped drawing frames while {keys} was held");
    }
}

#[test]
fn rom_frames_are_identical_to_the_host_renderer() {
    let mut checker = Checker {
        emulator: boot(),
        assets: demo::render_assets(),
        renderer: Renderer::new(),
        colours: MenuColours::from_palette(&portalcast_rom::assets::PALETTE),
        player: None,
        world: None,
        world_lines: WorldLines::default(),
        compared: Vec::new(),
        screenshots: BTreeSet::new(),
    };
    // The poses and settings come from the ROM's per-frame lines: switched on at power-on.
    for _ in FRAME_LINES_HOLD {
        checker.step(FRAME_LINES_KEY);
    }
    let (start, up, down, left, right) =
        (Keys::START, Keys::UP, Keys::DOWN, Keys::LEFT, Keys::RIGHT);
    // Each phase: menu presses (the cursor stays where it was left), then keys held until two
    // frames are compared, with the menu open or closed. The cursor starts on the resolution.
    let phases: [(&[Keys], Keys, bool); 10] = [
        (&[], right, false),                            // bench 120x80 depth, turning
        (&[start, right], Keys::NONE, true),            // menu open, 120x160
        (&[start], up | right, false),                  // bench 120x160 depth, walking
        (&[start, right, start], right, false),         // 240x160
        (&[start, down, right, start], left, false),    // lighting off
        (&[start, up, right, start], right, false),     // 120x80
        (&[start, down, right, start], up, false),      // lighting sector
        (&[start, down, right, start], right, false),   // map grid
        (&[start, right, start], up | left, false),     // map tiny
        (&[start, up, up, right, start], right, false), // 120x160 on tiny
    ];
    for (presses, hold, menu_open) in phases {
        for &key in presses {
            checker.press(key);
        }
        checker.hold_until_compared(hold, 2, menu_open);
    }
    // Back to the bench map through the menu.
    for key in [start, down, down, right, start] {
        checker.press(key);
    }
    checker.hold_until_compared(right, 2, false);
    // The quality knobs at the end of the menu: the textures from the cartridge, the scene
    // preprocessing, then half-width floors, which need 240×160 (four down from the
    // preprocessing wraps to the resolution, three up is the floors).
    let knob_phases: [&[Keys]; 5] = [
        &[start, down, down, down, right, start],
        &[start, down, right, start],
        &[
            start, down, down, down, down, right, up, up, up, right, start,
        ],
        // The HUD on: its figures are this frame's cycles, which the host reads from the line.
        &[start, down, right, start],
        // Things off, the last entry.
        &[start, down, right, start],
    ];
    for presses in knob_phases {
        for &key in presses {
            checker.press(key);
        }
        checker.hold_until_compared(right, 2, false);
    }

    let compared = &checker.compared;
    let maps: BTreeSet<&str> = compared.iter().map(|c| c.map.as_str()).collect();
    let compiled: BTreeSet<&str> = portalcast_rom::assets::MAPS
        .iter()
        .map(|m| m.name)
        .collect();
    assert_eq!(maps, compiled, "the menu must reach every shipped map");
    for lighting in ["depth", "off", "sector"] {
        assert!(
            compared
                .iter()
                .any(|c| demo::lighting_label(c.lighting) == lighting),
            "lighting {lighting} never compared"
        );
    }
    assert!(compared.iter().any(|c| c.menu), "no menu frame compared");
    assert!(
        compared.iter().any(|c| c.things_drawn > 0 && !c.menu),
        "no frame with a thing in view compared"
    );
    assert!(
        compared.iter().any(|c| c.middles_drawn > 0 && !c.menu),
        "no frame with a portal's middle image compared"
    );
    assert!(
        compared.iter().any(|c| c.translucent_drawn > 0 && !c.menu),
        "no frame with a translucent thing or middle compared"
    );
    for preprocessing in Preprocessing::ALL {
        assert!(
            compared.iter().any(|c| c.preprocessing == preprocessing),
            "preprocessing {preprocessing:?} never compared"
        );
    }
    for floors in Floors::ALL {
        assert!(
            compared
                .iter()
                .any(|c| c.floors == floors && c.resolution == Resolution::R240x160),
            "floors {floors:?} never compared at 240x160"
        );
    }
    assert!(
        compared.iter().any(|c| c.things == ThingsShown::Off),
        "no frame with things off compared"
    );
    assert!(
        compared.iter().any(|c| c.hud),
        "no frame with the HUD compared"
    );
    for textures in [TexturePlacement::Ewram, TexturePlacement::Rom] {
        assert!(
            compared.iter().any(|c| c.textures == textures),
            "textures {textures:?} never compared"
        );
    }
    for resolution in Resolution::ALL {
        let cycles: Vec<u64> = compared
            .iter()
            .filter(|c| c.resolution == resolution && !c.menu)
            .map(|c| c.cycles)
            .collect();
        assert!(!cycles.is_empty(), "{resolution:?} never compared");
        println!("{}: cycles per frame {:?}", resolution.label(), cycles);
    }
}
