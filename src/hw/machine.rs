//! A game's side of the machine in one value: [`Machine::start`] boots what the engine needs
//! (the wait states, the cycle timer, Mode 4, the VBlank button sampler, the code that runs from
//! VRAM, the textures and colormap in fast memory, the renderer's memory), [`Machine::ticks`]
//! hands out the buttons of every VBlank since the last frame, and [`Machine::draw`] draws a
//! frame into the back page and shows it. A game's own hardware (sprites, sound, its own
//! interrupts) goes alongside: [`Machine::display`], `input::chain`.
//!
//! ```ignore
//! let mut machine = Machine::start(&assets::ASSETS, ObjVram::Engine);
//! let map = &assets::MAPS[0];
//! let (mut player, mut controls) = (Player::spawn(map), Controls::new());
//! loop {
//!     machine.ticks(|held| player.tick(&controls.read(held), map));
//!     machine.draw(map, &player.camera(), &Settings::DEFAULT);
//! }
//! ```

use portalcast_format::{Assets, MapTables};

use super::kernels::{VramCanvas, VramPage};
use super::memory::{self, GbaRenderer};
use super::video::Display;
use super::{input, meter};
use crate::frame::Resolution;
use crate::player::input::Buttons;
use crate::render::view::{Camera, Settings, TexturePlacement, View};
use crate::render::walk::FrameStats;
use crate::render::RenderAssets;

/// Where the engine keeps the light colormap, which decides the OBJ tile VRAM a game gets for
/// hardware sprites. In Mode 4 the OBJ tiles are 512..1023, at 0x0601_4000..0x0601_8000: the
/// engine keeps its column windows and the code that runs from VRAM in their top half
/// (0x0601_6000..) whichever is chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ObjVram {
    /// The colormap in OBJ VRAM (0x0601_4000..0x0601_6000): a lit pixel's colormap read costs 1
    /// cycle; no OBJ tile is free.
    Engine,
    /// The colormap in EWRAM: OBJ tiles 512..767 (0x0601_4000..0x0601_6000, 8 KiB: 256 tiles of
    /// 16 colours or 128 of 256) are the game's, for sprites over the view (a HUD, a weapon). A
    /// lit pixel's colormap read costs 3 cycles (EWRAM) instead of 1.
    GameTiles,
}

/// The display, the renderer and the button sampler of a game, and its assets where the engine
/// reads them fastest. Start one once.
pub struct Machine {
    display: Display,
    renderer: &'static mut GbaRenderer,
    sampler: input::Sampler,
    fast: RenderAssets<'static>,
    cartridge: RenderAssets<'static>,
    ticks: u32,
}

impl Machine {
    /// Boots the engine's share of the machine for `assets` (the `ASSETS` of a game's compiled
    /// assets): Mode 4 at 120×80 with BG2 hidden until the first frame, `assets`' palette in
    /// the BG palette, the VBlank interrupt sampling the buttons, the textures the compiler
    /// placed in EWRAM copied there, the colormap where `obj_vram` says. Panics if called twice
    /// (the renderer's memory is handed out once).
    pub fn start(assets: &'static Assets<'static>, obj_vram: ObjVram) -> Machine {
        super::set_waitstates();
        meter::start();
        let display = Display::start(Resolution::R120x80);
        input::start();
        memory::code_in_vram();
        display.set_palette(assets.palette);
        let colormap = match obj_vram {
            ObjVram::Engine => memory::colormap_in_vram(assets.colormap),
            ObjVram::GameTiles => memory::colormap_in_ewram(assets.colormap),
        };
        let textures =
            memory::textures_in_ewram(assets.textures, assets.texel_blob, assets.texel_ewram_len);
        let cartridge = RenderAssets::from_assets(assets);
        Machine {
            display,
            renderer: memory::renderer_in_ewram(meter::now),
            sampler: input::Sampler::new(),
            fast: RenderAssets {
                textures,
                colormap,
                ..cartridge
            },
            cartridge,
            ticks: 0,
        }
    }

    /// The display: for the game's own DISPCNT bits ([`Display::with_control`]) and palette.
    pub fn display(&mut self) -> &mut Display {
        &mut self.display
    }

    /// The assets as [`Machine::draw`] reads them under `settings`' texture placement: from
    /// EWRAM and VRAM (the default), or from the cartridge.
    pub fn render_assets(&self, settings: &Settings) -> RenderAssets<'static> {
        match settings.textures {
            TexturePlacement::Ewram => self.fast,
            TexturePlacement::Rom => self.cartridge,
        }
    }

    /// Calls `each` with the buttons held at every VBlank since the last call, oldest first:
    /// one game tick each, so the game runs at 60 ticks a second whatever its frame rate.
    /// Returns how many ticks were lost (more than `input::RING_SAMPLES` VBlanks since the last
    /// call).
    pub fn ticks(&mut self, mut each: impl FnMut(Buttons)) -> u32 {
        let ticks = &mut self.ticks;
        self.sampler.drain(|_, held| {
            *ticks = ticks.wrapping_add(1);
            each(Buttons(held));
        })
    }

    /// Ticks handed out by [`Machine::ticks`] so far: the animations' clock.
    pub fn tick_count(&self) -> u32 {
        self.ticks
    }

    /// Draws `map` seen by `camera` with `settings` into the back page, then shows it at the
    /// next VBlank. Returns what the frame drew and its stages' cycles.
    ///
    /// Inline, so that the renderer's frame is compiled in the game's crate, as the shipped
    /// ROM's own call compiles it: compiled here, the engine's copy replaced the ROM's at the
    /// link and drew the bench map 0.3 % slower (its wall stage, laid out differently).
    #[inline]
    pub fn draw(&mut self, map: &MapTables, camera: &Camera, settings: &Settings) -> FrameStats {
        let view = View::new(camera, settings).at_tick(self.ticks);
        let page = VramPage::back_of(self.display.shown_page());
        let mut canvas = VramCanvas::new(page, settings.resolution);
        let assets = self.render_assets(settings);
        let stats = self.renderer.render(map, &assets, &view, &mut canvas);
        self.display.flip_at_vblank(settings.resolution);
        stats
    }
}
