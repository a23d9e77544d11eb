//! The portalcast ROM. It only builds for the GBA (`cargo rom`); a host build explains that.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "portalcast's binary is the GBA ROM: build it with `cargo rom` (writes target/portalcast.gba) \
         or run it with `cargo run` or `cargo play` at the repository's top."
    );
    std::process::exit(2);
}

#[cfg(target_os = "none")]
mod rom {
    use core::mem::MaybeUninit;
    use portalcast::frame::Resolution;
    use portalcast::hw::kernels::{VramCanvas, VramPage};
    use portalcast::hw::memory::{GbaRenderer, LentPageRows};
    use portalcast::hw::{self, input, log, memory, meter, video::Display};
    use portalcast::player::input::Buttons;
    use portalcast::render::view::{Settings, TexturePlacement, View};
    use portalcast::render::RenderAssets;
    use portalcast_format::MapTables;
    use portalcast_rom::bench::{self, BenchLine};
    use portalcast_rom::demo;
    use portalcast_rom::game::{Game, GameWorld};
    use portalcast_rom::live_flight::LiveFlight;
    use portalcast_rom::menu::{self, MenuColours};
    use portalcast_rom::{assets, kernel_check, testpic};

    const KEY_A: u16 = Buttons::A.0;
    const KEY_B: u16 = Buttons::B.0;
    const KEY_SELECT: u16 = Buttons::SELECT.0;
    const KEY_RIGHT: u16 = Buttons::RIGHT.0;
    const KEY_LEFT: u16 = Buttons::LEFT.0;
    const KEY_R: u16 = Buttons::R.0;
    const KEY_L: u16 = Buttons::L.0;
    /// Held at power-on (alone, or with keys no scene reads): the game writes its per-frame
    /// `player` and `render` lines ([`play_scene`]).
    const KEY_START: u16 = Buttons::START.0;

    /// Entered from gba's runtime after it copied IWRAM/EWRAM and zeroed .bss.
    #[allow(unsafe_code)]
    #[no_mangle]
    extern "C" fn main() -> ! {
        hw::set_waitstates();
        meter::start();
        let mut display = Display::start(Resolution::R120x80);
        input::start();
        // While the stack is shallow, everything below this frame gets the paint that the
        // stack's high-water mark is read from. After the sampler starts: the paint takes a
        // while, and the sampler's VBlank count must start on the emulator's first frame.
        memory::paint_stack();
        // After the sampler starts, so its VBlank count is the emulator's frame count whatever
        // the boot checks cost (the player's emulator tests rely on it).
        log::info(format_args!(
            "portalcast boot waitcnt=0x{:04x} iwram_used={} stack_room={} ewram_used={} division_digest=0x{:08x} game_bytes={} live_sectors={} sector_bytes={} live_movers={} mover_state_bytes={} live_triggers={} trigger_bytes={}",
            hw::WAITCNT_SETTING,
            memory::iwram_used(),
            memory::stack_room(),
            memory::ewram_used(),
            portalcast_rom::selfcheck::division_digest(),
            core::mem::size_of::<Game>(),
            assets::LIVE_SECTORS,
            core::mem::size_of::<portalcast_format::Sector>(),
            assets::LIVE_MOVERS,
            core::mem::size_of::<portalcast::world::MoverState>(),
            assets::LIVE_TRIGGERS,
            core::mem::size_of::<portalcast_format::Trigger>(),
        ));

        let held_at_boot = hw::keys_held();
        // After the boot keys are read (a test holds them for the first frames only), before any
        // scene: the soak test's guard over OBJ VRAM reads the copy as the game starts, and
        // nothing may write there afterwards.
        memory::colormap_in_vram(&assets::COLORMAP.0);
        memory::code_in_vram();
        if held_at_boot & (KEY_L | KEY_R | KEY_A) == KEY_L | KEY_R | KEY_A {
            machine_check_scene(&mut display);
        }
        if held_at_boot & (KEY_L | KEY_R) == KEY_L | KEY_R {
            display.set_palette(&testpic::PALETTE);
            kernel_check_scene(&mut display);
        }
        if held_at_boot & (KEY_L | KEY_R) == KEY_R {
            display.set_palette(&assets::PALETTE);
            bench_scene(&mut display, held_at_boot & KEY_SELECT != 0);
        }
        if held_at_boot & (KEY_L | KEY_R) == KEY_L {
            display.set_palette(&testpic::PALETTE);
            math_scene(&mut display);
        }
        if held_at_boot & KEY_B != 0 {
            display.set_palette(&testpic::PALETTE);
            test_picture_scene(&mut display, held_at_boot);
        }
        let frame_lines = held_at_boot & KEY_START != 0;
        if frame_lines {
            wait_for_release(&display, held_at_boot);
        }
        display.set_palette(&assets::PALETTE);
        play_scene(&mut display, frame_lines)
    }

    /// Start held at power-on: waits, VBlank by VBlank, until it is let go, so the press that
    /// chose the per-frame lines never reaches the game (it would open the menu). Then prints
    /// `input boot keys=0x… released_vblank=K`: the sample of VBlank `K` was the first without
    /// Start, so a replay that holds the boot keys on emulator frames `0..=K` leaves the wait on
    /// the same VBlank and replays the game exactly (`KeyScript::from_rom_log` in the harness).
    /// The test right after each VBlank, never before the first, is what makes `K` a function
    /// of the frames Start was held on, not of where the boot code happened to be.
    fn wait_for_release(display: &Display, held_at_boot: u16) {
        loop {
            display.wait_vblank();
            if hw::keys_held() & KEY_START == 0 {
                break;
            }
        }
        log::info(format_args!(
            "input boot keys=0x{held_at_boot:03x} released_vblank={}",
            input::samples_written().wrapping_sub(1)
        ));
    }

    /// The game: the player on the bench map (the menu switches maps and settings). The
    /// buttons are sampled at every VBlank and the game runs one tick per sample, so it runs at
    /// 60 ticks per second whatever the frame rate; then one frame shows the result.
    ///
    /// What goes to mGBA's log:
    /// - always, an `input vblank=… keys=…` line for every change of the buttons: a recording of
    ///   the game that a harness key script replays (a player can send one with a bug report;
    ///   it costs only when the buttons change);
    /// - always, about once a second, a `rate …` line ([`RateWindow`]): the frame rate the
    ///   player gets and what the frame's parts and the log lines cost;
    /// - with `frame_lines` (Start held at power-on), two lines per frame (one would pass the
    ///   256 bytes of mGBA's debug string register): `player …` with the pose after the
    ///   frame's ticks, then `render …`. The emulator tests and the soak read them; formatting
    ///   them costs tens of thousands of cycles a frame, which a player should not pay, so
    ///   without the switch they are not formatted at all.
    fn play_scene(display: &mut Display, frame_lines: bool) -> ! {
        let renderer = memory::renderer_in_ewram(meter::now);
        let colours = MenuColours::from_palette(&assets::PALETTE);
        let game = game_in_ewram(assets::MAPS);
        // Everything the scene keeps in EWRAM is handed out before it starts, so the
        // `ewram_used` of its start line is final (the soak guards the EWRAM above it).
        LentPageRows::prepare(textures_in_ewram().len());
        let mut sampler = input::Sampler::new();
        // What the two timer reads around a tick cost with nothing between them: taken off
        // each tick's figure, so `tick_cycles` counts the tick alone.
        let timer_cycles = {
            let started = meter::now();
            meter::cycles_since(started)
        };
        log::info(format_args!(
            "play start vblank={} map={} timer_cycles={timer_cycles} frame_lines={} ewram_used={}",
            sampler.next_index(),
            game.map_name(),
            u8::from(frame_lines),
            memory::ewram_used()
        ));
        let mut rate = RateWindow::new(sampler.next_index());
        let mut frame: u32 = 0;
        let mut stack_reported = 0;
        let mut lent = None;
        loop {
            let game_started = meter::now();
            let mut ticks = TickCycles::default();
            let lost = sampler.drain(|vblank, held| {
                // The recording: every change of the buttons, which replays the game exactly
                // (`KeyScript::from_rom_log` in the harness).
                if held != game.held().0 {
                    let started = meter::now();
                    log::info(format_args!("input vblank={vblank} keys=0x{held:03x}"));
                    rate.input_lines_cycles += meter::cycles_since(started);
                }
                // Each tick timed alone, so the figures leave out the recording's log lines
                // and the frame's other work.
                let started = meter::now();
                game.tick(Buttons(held));
                ticks.add(meter::cycles_since(started).saturating_sub(timer_cycles));
            });
            let game_cycles = meter::cycles_since(game_started);
            let camera = game.camera();
            game.show();
            if frame_lines {
                let started = meter::now();
                log_player_line(frame, sampler.next_index(), lost, game, game_cycles, &ticks);
                if game.world.is_live() {
                    let map = game.map();
                    let (movers, triggers) = (game.world.movers(), game.world.triggers());
                    // In parts of a few items of each list: a map with many movers would
                    // overflow mGBA's 256-byte log line.
                    let longest = movers.len().max(triggers.len()).max(map.lights.len());
                    let parts = longest.div_ceil(WORLD_LINE_ITEMS).max(1);
                    for part in 0..parts {
                        let skip = part * WORLD_LINE_ITEMS;
                        log::info(format_args!(
                            "world frame={frame} part={}/{parts} heights={} thrown={} lights={}",
                            part + 1,
                            Joined(
                                movers
                                    .iter()
                                    .skip(skip)
                                    .take(WORLD_LINE_ITEMS)
                                    .map(|mover| mover.height)
                            ),
                            Joined(
                                triggers
                                    .iter()
                                    .skip(skip)
                                    .take(WORLD_LINE_ITEMS)
                                    .map(|trigger| trigger.thrown)
                            ),
                            Joined(game.world.lights(&map).skip(skip).take(WORLD_LINE_ITEMS))
                        ));
                    }
                }
                rate.frame_lines_cycles += meter::cycles_since(started);
            }
            let settings = game.settings;
            let view = View::new(&camera, &settings).at_tick(game.ticks());
            keep_rows_lent(&mut lent, display, &settings);
            let page = VramPage::back_of(display.shown_page());
            let address = page.address();
            let mut canvas = VramCanvas::new(page, settings.resolution);
            let started = meter::now();
            let render_assets = with_lent_rows(
                demo::assets_for(settings.textures, assets_in_fast_memory),
                &lent,
            );
            let stats = renderer.render(&game.map(), &render_assets, &view, &mut canvas);
            let cycles = meter::cycles_since(started);
            if game.hud {
                menu::draw_hud(&mut canvas, &menu::hud_line(cycles), colours);
            }
            if let Some(text) = game.menu_text() {
                menu::draw(&mut canvas, &text, colours);
            }
            display.flip_at_vblank(settings.resolution);
            if frame_lines {
                let started = meter::now();
                log::info(format_args!(
                    "render map={} frame={frame} {} page=0x{address:08x} cycles={cycles} wall_cycles={} plane_cycles={} visits={} columns={} span_px={} column_px={} sprites={}",
                    game.map_name(),
                    bench::SettingsLabel(&settings),
                    stats.wall_ticks,
                    stats.plane_ticks,
                    stats.sector_visits,
                    stats.wall_columns,
                    stats.span_pixels,
                    stats.column_pixels,
                    stats.things_drawn,
                ));
                rate.frame_lines_cycles += meter::cycles_since(started);
            }
            rate.add_frame(game_cycles, cycles);
            frame = frame.wrapping_add(1);
            if frame.is_multiple_of(STACK_CHECK_FRAMES) {
                let used = memory::stack_high_water();
                if used > stack_reported {
                    stack_reported = used;
                    log_stack();
                }
            }
            rate.log_if_due(input::samples_written());
        }
    }

    /// The `player …` line of a frame (see [`play_scene`]): the pose and state after the
    /// frame's ticks, which the emulator tests compare with the host's replay, and the ticks'
    /// cycles that `cargo bench-tick` adds up.
    fn log_player_line(
        frame: u32,
        vblank: u32,
        lost: u32,
        game: &Game,
        game_cycles: u32,
        ticks: &TickCycles,
    ) {
        let camera = game.camera();
        let player = &game.player;
        log::info(format_args!(
                "player frame={frame} vblank={vblank} tick={} lost={lost} keys=0x{:03x} x={} y={} z={} angle={} sector={} look={} ground={} crouch={} fly={} run={} menu={} hud={} game_cycles={game_cycles} ticks={} tick_cycles={} tick_max_cycles={}",
                game.ticks(),
                game.held().0,
                camera.position.x.to_bits(),
                camera.position.y.to_bits(),
                camera.eye_z.to_bits(),
                camera.angle.to_bits(),
                camera.sector,
                camera.look_lines,
                u8::from(player.on_ground),
                u8::from(player.crouched()),
                u8::from(player.fly),
                u8::from(game.controls.always_run),
                if game.menu.open { game.menu.cursor as i32 } else { -1 },
                u8::from(game.hud),
                ticks.count,
                ticks.total,
                ticks.max,
            ));
    }

    /// Items written as `a,b,c` (nothing where there are none): the `world …` line's lists
    /// (movers' heights, switches thrown, light effects' levels), so the tests draw the frame
    /// the ROM drew.
    struct Joined<I>(I);

    impl<I: Clone + Iterator> core::fmt::Display for Joined<I>
    where
        I::Item: core::fmt::Display,
    {
        fn fmt(&self, f: &mut core::fmt::Formatter) -> core::fmt::Result {
            for (index, item) in self.0.clone().enumerate() {
                if index > 0 {
                    f.write_str(",")?;
                }
                write!(f, "{item}")?;
            }
            Ok(())
        }
    }

    /// Items of each list a `world` log line holds: 12 heights (up to 6 characters each), 12
    /// switches and 12 light levels keep a line within mGBA's 256 bytes.
    const WORLD_LINE_ITEMS: usize = 12;

    /// VBlanks a [`RateWindow`] spans at least: one second of the GBA's 59.73 Hz display.
    const RATE_VBLANKS: u32 = 60;

    /// CPU cycles per second of the GBA (2^24), and per displayed frame (228 lines of 1232
    /// cycles): the refresh rate is their ratio, 59.73 Hz.
    const CPU_HZ: u64 = 1 << 24;
    const CYCLES_PER_VBLANK: u64 = 280_896;

    /// The frames drawn since the last `rate` line and what they cost. Once at least
    /// [`RATE_VBLANKS`] VBlanks have passed, [`RateWindow::log_if_due`] prints
    /// `rate vblank=V vblanks=N frames=F fps=X.XX` and the per-frame means of the render, the
    /// game ticks and the two kinds of log lines, plus what the previous `rate` line cost: so a
    /// player in mGBA reads the frame rate they get, `cargo play` prints it, and docs/BENCH.md
    /// measures what the per-frame lines cost (`cargo bench-logging`). One line a second, not
    /// a line a frame: its own cost is printed on the next one.
    struct RateWindow {
        /// The VBlank count ([`input::samples_written`]) the window started at.
        since_vblank: u32,
        frames: u32,
        render_cycles: u32,
        game_cycles: u32,
        /// Cycles spent formatting and writing the `player` and `render` lines (0 without the
        /// switch: they are not written).
        frame_lines_cycles: u32,
        /// Cycles spent on the recording's `input` lines.
        input_lines_cycles: u32,
        /// What the previous `rate` line cost.
        last_line_cycles: u32,
    }

    impl RateWindow {
        fn new(vblank: u32) -> RateWindow {
            RateWindow {
                since_vblank: vblank,
                frames: 0,
                render_cycles: 0,
                game_cycles: 0,
                frame_lines_cycles: 0,
                input_lines_cycles: 0,
                last_line_cycles: 0,
            }
        }

        fn add_frame(&mut self, game_cycles: u32, render_cycles: u32) {
            self.frames += 1;
            self.game_cycles = self.game_cycles.wrapping_add(game_cycles);
            self.render_cycles = self.render_cycles.wrapping_add(render_cycles);
        }

        /// Prints the `rate` line and starts a new window if the window spans
        /// [`RATE_VBLANKS`] by `vblank` (the VBlanks sampled so far).
        fn log_if_due(&mut self, vblank: u32) {
            let vblanks = vblank.wrapping_sub(self.since_vblank);
            if vblanks < RATE_VBLANKS {
                return;
            }
            let started = meter::now();
            let frames = self.frames.max(1);
            // Frames per second in hundredths: frames over the window's duration in seconds.
            // Printed as a u32: core's u64 formatting is Thumb code that calls __aeabi_lmul,
            // which linker.ld puts in IWRAM (88 bytes of the stack's room).
            let fps_x100 = (u64::from(self.frames) * 100 * CPU_HZ
                / (u64::from(vblanks) * CYCLES_PER_VBLANK)) as u32;
            log::info(format_args!(
                "rate vblank={vblank} vblanks={vblanks} frames={} fps={}.{:02} mean_render_cycles={} mean_game_cycles={} mean_frame_lines_cycles={} mean_input_lines_cycles={} rate_line_cycles={}",
                self.frames,
                fps_x100 / 100,
                fps_x100 % 100,
                self.render_cycles / frames,
                self.game_cycles / frames,
                self.frame_lines_cycles / frames,
                self.input_lines_cycles / frames,
                self.last_line_cycles,
            ));
            *self = RateWindow::new(vblank);
            self.last_line_cycles = meter::cycles_since(started);
        }
    }

    /// The cycles of the ticks run before one frame, printed as `ticks=` (how many),
    /// `tick_cycles=` (their sum) and `tick_max_cycles=` on the `player` line: `cargo bench-tick`
    /// adds them up over a walk for the mean and worst tick.
    #[derive(Default)]
    struct TickCycles {
        count: u32,
        total: u32,
        max: u32,
    }

    impl TickCycles {
        fn add(&mut self, cycles: u32) {
            self.count += 1;
            self.total = self.total.wrapping_add(cycles);
            self.max = self.max.max(cycles);
        }
    }

    /// How often the game reads the stack's high-water mark (a scan of up to 8 KB of IWRAM); it
    /// prints a `stack …` line when the mark has grown.
    const STACK_CHECK_FRAMES: u32 = 64;

    /// `stack used=U room=R reserve=S`: the deepest the stack has gone since boot (the paint it
    /// left intact, [`memory::stack_high_water`]) against the room the linker left it and the
    /// reserve its script keeps for it.
    fn log_stack() {
        log::info(format_args!(
            "stack used={} room={} reserve={}",
            memory::stack_high_water(),
            memory::stack_room(),
            memory::stack_reserve()
        ));
    }

    /// R held at boot: the benchmark. Every run of [`bench::all_runs`] (with Select also held,
    /// only the regression guard's, [`bench::guard_runs`]) flies
    /// the map's [`LiveFlight`] for [`bench::frames_for`] frames, one line per frame, then
    /// `bench done`. `cargo bench-report` and the guard test read the lines.
    fn bench_scene(display: &mut Display, guard_only: bool) -> ! {
        let renderer = memory::renderer_in_ewram(meter::now);
        let world = memory::ewram_uninit().write(const { GameWorld::new() });
        let flight = memory::ewram_uninit();
        let mut run = |(map, settings): (&'static MapTables<'static>, Settings), kernels: bool| {
            let render_assets = demo::assets_for(settings.textures, assets_in_fast_memory);
            // Started here, not in `bench_run`: its construction is the scene's deepest stack.
            let flight = start_flight(flight, map, world);
            bench_run(
                display,
                renderer,
                world,
                flight,
                &render_assets,
                map,
                &settings,
                kernels,
            );
        };
        bench::guard_runs().for_each(|guarded| run(guarded, true));
        log::info(format_args!("{}", bench::GUARD_DONE));
        if !guard_only {
            bench::report_runs().for_each(|reported| run(reported, true));
            bench::setup_runs().for_each(|set_up| run(set_up, false));
        }
        log_stack();
        log::info(format_args!("{}", bench::BENCH_DONE));
        loop {
            display.wait_vblank();
        }
    }

    /// One setting of the benchmark. A first, unmeasured frame fills the renderer's per-resolution
    /// tables (the column angles), so the figures are the steady per-frame cost. With `kernels`
    /// false (the set-up runs) the frames go to a canvas that runs no kernel
    /// ([`VramCanvas::without_kernels`]) and print as [`bench::SetupLine`]s.
    #[allow(clippy::too_many_arguments)]
    fn bench_run(
        display: &mut Display,
        renderer: &mut GbaRenderer,
        world: &mut GameWorld,
        flight: &mut LiveFlight<'static>,
        render_assets: &RenderAssets,
        map: &'static MapTables<'static>,
        settings: &Settings,
        kernels: bool,
    ) {
        // The first frame, unmeasured, is frame 0 drawn once more; the page rows are lent
        // after it, when the display shows its resolution.
        let mut lent = None;
        for index in 0..=bench::frames_for(map) {
            if index == 1 && kernels {
                keep_rows_lent(&mut lent, display, settings);
                if let Some(held) = lent.as_ref().map(LentPageRows::held) {
                    log::info(format_args!(
                        "page rows lent chains={} bytes={}",
                        held.0, held.1
                    ));
                }
            }
            let render_assets = &with_lent_rows(*render_assets, &lent);
            let camera = flight.camera();
            // The fly-through's clock: a tick a frame.
            let view = View::new(&camera, settings).at_tick(flight.frame());
            let page = VramPage::back_of(display.shown_page());
            let mut canvas = if kernels {
                VramCanvas::new(page, settings.resolution)
            } else {
                VramCanvas::without_kernels(page, settings.resolution)
            };
            let started = meter::now();
            let stats = renderer.render(&world.map(map), render_assets, &view, &mut canvas);
            let cycles = meter::cycles_since(started);
            if kernels {
                display.flip_at_vblank(settings.resolution);
            }
            if index > 0 {
                let line = BenchLine {
                    map: map.name,
                    settings,
                    frame: index - 1,
                    cycles,
                    stats: &stats,
                };
                if kernels {
                    log::info(format_args!("{line}"));
                } else {
                    log::info(format_args!("{}", bench::SetupLine(line)));
                }
                flight.advance(world);
            }
        }
    }

    /// A run's fly-through of `map`, written to `slot`. Out of line: the flight is built in this
    /// function's frame before it is copied, and in [`bench_run`]'s that copy would sit under the
    /// renderer's frames for the whole run.
    #[inline(never)]
    fn start_flight<'f>(
        slot: &'f mut MaybeUninit<LiveFlight<'static>>,
        map: &'static MapTables<'static>,
        world: &mut GameWorld,
    ) -> &'f mut LiveFlight<'static> {
        slot.write(LiveFlight::new(map, world))
    }

    /// Keeps the page rows a low frame leaves free lent to the hottest texture chains
    /// ([`LentPageRows`]) while the frames are that low, their textures in fast memory, and the
    /// display already shows such a frame (so the copy never shows on screen); gives them back
    /// before any other frame. Out of line: its copy's temporaries stay off the renderer's
    /// stack.
    #[inline(never)]
    fn keep_rows_lent(lent: &mut Option<LentPageRows>, display: &Display, settings: &Settings) {
        let low = |resolution: Resolution| resolution.height() <= memory::LENT_FROM_ROW;
        if !(low(settings.resolution)
            && low(display.shown_resolution())
            && settings.textures == TexturePlacement::Ewram)
        {
            *lent = None;
        } else if lent.is_none() {
            *lent = LentPageRows::lend(textures_in_ewram(), assets::TEXTURE_CHAINS_BY_HEAT);
        }
    }

    /// `assets`, the textures read from the lent page rows where `lent` holds them.
    fn with_lent_rows<'l>(
        assets: RenderAssets<'l>,
        lent: &'l Option<LentPageRows>,
    ) -> RenderAssets<'l> {
        match lent {
            Some(lent) => RenderAssets {
                textures: lent.textures(),
                ..assets
            },
            None => assets,
        }
    }

    /// The textures copied to EWRAM and the colormap to OBJ VRAM (once), for
    /// [`demo::assets_for`].
    fn assets_in_fast_memory() -> (
        &'static [portalcast_format::Texture<'static>],
        &'static portalcast_format::Colormap,
    ) {
        (
            textures_in_ewram(),
            memory::colormap_in_vram(&assets::COLORMAP.0),
        )
    }

    /// The textures, those the asset compiler placed in EWRAM copied there (once).
    fn textures_in_ewram() -> &'static [portalcast_format::Texture<'static>] {
        memory::textures_in_ewram(
            assets::TEXTURES,
            &assets::TEXEL_BLOB.0,
            assets::TEXEL_EWRAM_LEN,
        )
    }

    /// The game on `maps`, in EWRAM: with a map's live sector table
    /// ([`portalcast::world::World`]) it is too large for the stack's room in IWRAM. The blank
    /// game is a constant: written without a copy on the stack, then started in place.
    fn game_in_ewram(maps: &'static [MapTables<'static>]) -> &'static mut Game<'static> {
        let game = memory::ewram_uninit().write(const { Game::blank(&[]) });
        game.set_maps(maps);
        game.start();
        game
    }

    // The EWRAM the asset compiler gives textures (`portalcast_format::memory`) is what the
    // ROM's own state leaves: a renderer or game grown past its share stops the build here,
    // naming the constant, rather than at run time.
    const _: () = {
        use portalcast_format::memory::{
            ewram_texel_budget, live_state_bytes, EWRAM_ENGINE_BYTES, TEXTURE_ENTRY_BYTES,
        };
        let live_state = live_state_bytes(
            assets::LIVE_SECTORS,
            assets::LIVE_MOVERS,
            assets::LIVE_TRIGGERS,
        );
        assert!(
            core::mem::size_of::<GbaRenderer>()
                + core::mem::size_of::<Game>()
                + core::mem::size_of::<GameWorld>()
                + core::mem::size_of::<LiveFlight>()
                <= EWRAM_ENGINE_BYTES + live_state,
            "the renderer's, the game's and the bench's EWRAM outgrew EWRAM_ENGINE_BYTES (crates/format/src/memory.rs)"
        );
        assert!(core::mem::size_of::<portalcast_format::Texture<'static>>() <= TEXTURE_ENTRY_BYTES);
        assert!(assets::TEXEL_EWRAM_LEN <= ewram_texel_budget(assets::TEXTURE_COUNT, live_state));
    };

    /// B held at boot: the foundation's test picture. Select cycles the resolution, left/right
    /// scroll.
    fn test_picture_scene(display: &mut Display, held_at_boot: u16) -> ! {
        let mut resolution = Resolution::R120x80;
        let mut phase: u32 = 0;
        let mut held_before: u16 = held_at_boot;
        let mut frame: u32 = 0;
        loop {
            let held = hw::keys_held();
            let pressed = held & !held_before;
            held_before = held;
            if pressed & KEY_SELECT != 0 {
                resolution = resolution.next();
            }
            if held & KEY_RIGHT != 0 {
                phase = phase.wrapping_add(1);
            }
            if held & KEY_LEFT != 0 {
                phase = phase.wrapping_sub(1);
            }

            let started = meter::now();
            let mut back = VramPage::back_of(display.shown_page());
            testpic::draw(&mut back, resolution, phase);
            let draw_cycles = meter::cycles_since(started);

            display.flip_at_vblank(resolution);
            frame += 1;
            log::info(format_args!(
                "shown frame={frame} res={} phase={phase} draw_cycles={draw_cycles}",
                resolution.label()
            ));
        }
    }

    /// Flips the machine check makes before its panic.
    const MACHINE_CHECK_FLIPS: u32 = 30;
    /// VBlanks the machine check's own interrupt handler has seen.
    static CHAINED_VBLANKS: gba::prelude::GbaCell<u32> = gba::prelude::GbaCell::new(0);

    extern "C" fn count_vblank(bits: gba::interrupts::IrqBits) {
        if bits.vblank() {
            CHAINED_VBLANKS.write(CHAINED_VBLANKS.read().wrapping_add(1));
        }
    }

    /// L, R and A held at boot: what a game built on the engine does with the machine besides
    /// the view (tests/emulator_machine.rs). It chains an interrupt handler of its own, turns on
    /// the OBJ layer, flips [`MACHINE_CHECK_FLIPS`] times, prints `machine flips=… mode4=… bg2=…
    /// obj=… obj_1d=… chained_vblanks=… sampled_vblanks=…` (DISPCNT's bits after the flips; the VBlanks its handler
    /// and the engine's sampler saw meanwhile), then panics on purpose: the panic screen.
    fn machine_check_scene(display: &mut Display) -> ! {
        let first = hw::without_interrupts(|| {
            input::chain(Some(count_vblank));
            input::samples_written()
        });
        display.with_control(|control| control.with_show_obj(true).with_obj_vram_1d(true));
        for _ in 0..MACHINE_CHECK_FLIPS {
            display.flip_at_vblank(Resolution::R120x80);
        }
        let (chained, sampled) = hw::without_interrupts(|| {
            (
                CHAINED_VBLANKS.read(),
                input::samples_written().wrapping_sub(first),
            )
        });
        let control = display.control();
        log::info(format_args!(
            "machine flips={MACHINE_CHECK_FLIPS} mode4={} bg2={} obj={} obj_1d={} chained_vblanks={chained} sampled_vblanks={sampled}",
            u8::from(control.video_mode() == gba::prelude::VideoMode::_4),
            u8::from(control.show_bg2()),
            u8::from(control.show_obj()),
            u8::from(control.obj_vram_1d()),
        ));
        panic!("the machine check's deliberate panic, after {MACHINE_CHECK_FLIPS} flips")
    }

    /// L+R held at boot: draw the kernel check at every resolution with a few seeds, printing
    /// where each page is, so the emulator test can compare VRAM with the host twins.
    fn kernel_check_scene(display: &mut Display) -> ! {
        measure_kernels(display);
        let mut seed = 1u32;
        loop {
            // How deep the measurement and the draws have taken the stack (the measurement's
            // texels and colormap live on it), for tests/emulator_foundation.rs to hold against
            // the linker's reserve: once after the measurement, then after each round.
            log_stack();
            for resolution in Resolution::ALL {
                let mut page = VramPage::back_of(display.shown_page());
                page.clear();
                let address = page.address();
                let started = meter::now();
                kernel_check::draw(&mut VramCanvas::new(page, resolution), seed);
                let cycles = meter::cycles_since(started);
                display.flip_at_vblank(resolution);
                log::info(format_args!(
                    "kernel-check res={} seed={seed} page=0x{address:08x} cycles={cycles}",
                    resolution.label()
                ));
                // Hold the page on screen for a frame so the test reads it before it is reused.
                display.wait_vblank();
                display.wait_vblank();
                seed = seed.wrapping_add(1);
            }
        }
    }

    /// Cycles per pixel of the main kernel variants, with texels and colormap in IWRAM (on the
    /// stack): the difference between a 160-pixel and a 32-pixel run, divided by 128, so the
    /// call and set-up cost cancels. Printed in hundredths of a cycle. The flat is 32 texels a
    /// side (1 KB): a kernel's instructions are the same at every size, and a 64-texel flat's
    /// 4 KB on the stack left the scene less than the stack reserve.
    fn measure_kernels(display: &mut Display) {
        use portalcast::raster::column::ColumnTexture;
        use portalcast::raster::flat::{FlatTexture, PackedUv};
        use portalcast::raster::Canvas;
        let mut texels = [0u8; 1024];
        for (index, texel) in texels.iter_mut().enumerate() {
            *texel = (index * 37 % 251) as u8;
        }
        let colormap: [u8; 256] = core::array::from_fn(|index| (255 - index) as u8);
        let lab_column = |lit: bool| ColumnTexture {
            texels: &texels[..64],
            log2_height: 6,
            v: 0,
            dv: 0x0123_4567,
            colormap: if lit { Some(&colormap) } else { None },
        };
        let column_cost = |canvas: &mut VramCanvas, lit: bool, x: usize| {
            // The kernel bank of the lighting measured, brought in before the clock starts.
            canvas.prefer_lighting(lit);
            let mut run = |count: usize| {
                let column = lab_column(lit);
                let started = meter::now();
                canvas.column(x, 0, count, &column);
                meter::cycles_since(started)
            };
            (run(160) - run(32)) * 100 / 128
        };
        let flat_cost = |canvas: &mut VramCanvas, lit: bool| {
            canvas.prefer_lighting(lit);
            let mut run = |count: usize| {
                let flat = FlatTexture {
                    texels: &texels,
                    log2_side: 5,
                    pos: PackedUv(0),
                    step: PackedUv::pack(0x1_2345, -0x0_4321, 5),
                    colormap: if lit { Some(&colormap) } else { None },
                };
                let started = meter::now();
                canvas.flat(0, 0, count, &flat);
                meter::cycles_since(started)
            };
            (run(160) - run(32)) * 100 / 128
        };
        let page = || VramPage::back_of(display.shown_page());
        let mut doubled = VramCanvas::new(page(), Resolution::R120x160);
        let (col_unlit, col_lit) = (
            column_cost(&mut doubled, false, 7),
            column_cost(&mut doubled, true, 7),
        );
        let mut native = VramCanvas::new(page(), Resolution::R240x160);
        let col_native_lit = column_cost(&mut native, true, 7);
        // Two neighbouring columns at once, per pixel of the two.
        let col_pair_lit = {
            native.prefer_lighting(true);
            let mut run = |count: usize| {
                let column = lab_column(true);
                let started = meter::now();
                native.column_pair(6, (0, count, &column), (0, count, &column));
                meter::cycles_since(started)
            };
            (run(160) - run(32)) * 100 / 256
        };
        let mut wide = VramCanvas::new(page(), Resolution::R240x160);
        let (flat_pair_unlit, flat_pair_lit) =
            (flat_cost(&mut wide, false), flat_cost(&mut wide, true));
        // 160 doubled pixels do not fit a 120-wide row: measure the doubled span on 120 vs 32.
        let flat_dbl = |canvas: &mut VramCanvas, lit: bool| {
            canvas.prefer_lighting(lit);
            let mut run = |count: usize| {
                let flat = FlatTexture {
                    texels: &texels,
                    log2_side: 5,
                    pos: PackedUv(0),
                    step: PackedUv::pack(0x1_2345, -0x0_4321, 5),
                    colormap: if lit { Some(&colormap) } else { None },
                };
                let started = meter::now();
                canvas.flat(0, 0, count, &flat);
                meter::cycles_since(started)
            };
            (run(120) - run(24)) * 100 / 96
        };
        let (flat_dbl_unlit, flat_dbl_lit) =
            (flat_dbl(&mut doubled, false), flat_dbl(&mut doubled, true));
        // A sprite column of one post, a texel a row: 160 rows against 32 (translucent: over
        // the page, through a blend table, which any 64 KiB of the cartridge can stand in for).
        let blend: Option<&portalcast_format::BlendTable> =
            portalcast_rom::assets::BLEND.or_else(|| {
                portalcast_rom::assets::SKY
                    .and_then(|sky| sky.texels.get(..65536))
                    .and_then(|bytes| bytes.as_chunks::<256>().0.try_into().ok())
            });
        let sprite_cost = |canvas: &mut VramCanvas, x: usize, blend| {
            let mut run = |count: usize| {
                let mut posts = [0u8; 4 + 160];
                posts[..3].copy_from_slice(&[1, 0, count as u8]);
                posts[3..3 + count + 1].copy_from_slice(&texels[..count + 1]);
                let column = portalcast::raster::sprite::SpriteColumn {
                    posts: &posts,
                    y_top: 0,
                    scale: 1 << 16,
                    iscale: 1 << 16,
                    clip: portalcast::raster::Window {
                        top: 0,
                        bottom: count as i16,
                    },
                    colormap: &colormap,
                    blend,
                };
                let started = meter::now();
                canvas.sprite_column(x, &column);
                meter::cycles_since(started)
            };
            (run(160) - run(32)) * 100 / 128
        };
        let sprite_dbl = sprite_cost(&mut doubled, 7, None);
        let sprite_native = sprite_cost(&mut native, 7, None);
        let sprite_blend_dbl = blend.map_or(0, |table| sprite_cost(&mut doubled, 7, Some(table)));
        log::info(format_args!(
            "kernel-cycles-x100 col_dbl_unlit={col_unlit} col_dbl_lit={col_lit} col_native_lit={col_native_lit} col_pair_lit={col_pair_lit} \
             flat_dbl_unlit={flat_dbl_unlit} flat_dbl_lit={flat_dbl_lit} flat_pair_unlit={flat_pair_unlit} flat_pair_lit={flat_pair_lit} \
             sprite_dbl={sprite_dbl} sprite_native={sprite_native} sprite_blend_dbl={sprite_blend_dbl}"
        ));
    }

    /// Rounds of the two timed runs of every benchmark loop. A figure is the difference of the
    /// two runs divided by the operations it adds (8 rounds of 16 pairs), so the call, the
    /// set-up and the timer reads cancel.
    const MATH_SHORT_ROUNDS: u32 = 1;
    const MATH_LONG_ROUNDS: u32 = 9;

    /// L held at boot: the math micro-benchmark (`portalcast::math_bench`). For every
    /// operation: check that its variants (the Thumb loop in ROM, the same loop in IWRAM, the
    /// ARM routine) give the same results pair by pair, then time each, interrupts masked, and
    /// print cycles per operation in hundredths. `cargo bench-math` turns the lines into the
    /// math section of docs/BENCH.md; tests/emulator_math.rs checks them.
    fn math_scene(display: &mut Display) -> ! {
        use core::hint::black_box;
        use portalcast::hw::math_bench::BenchCode;
        use portalcast::math_bench::{mix, Op, Pair, INPUTS};

        // SAFETY: the overlay replaces the renderer's per-frame code; this scene draws nothing
        // and never returns (its caller would go on to the game).
        let code = unsafe { BenchCode::load() };
        let code_mode = if cfg!(target_feature = "thumb-mode") {
            "thumb"
        } else {
            "arm"
        };
        log::info(format_args!(
            "math begin code={code_mode} overlay_bytes={} pairs={INPUTS} rounds={MATH_SHORT_ROUNDS}-{MATH_LONG_ROUNDS}",
            code.bytes()
        ));
        for op in Op::ALL {
            let mut inputs = op.inputs();
            // Opaque, so the pairs stay in this stack copy (IWRAM) rather than being read from
            // their constant in ROM, which would add the cart's wait states to every load.
            black_box(&mut inputs);
            assert_eq!(
                inputs.as_ptr() as usize >> 24,
                0x03,
                "operands not in IWRAM"
            );

            type Run<'a> = &'a dyn Fn(&[Pair], u32) -> i32;
            let in_rom: Run = &|pairs, rounds| op.run_in_rom(pairs, rounds);
            let in_iwram: Run = &|pairs, rounds| code.run_in_iwram(op, pairs, rounds);
            let arm: Run = &|pairs, rounds| code.run_arm(op, pairs, rounds).unwrap_or(0);

            let check = |run: Run| mix(inputs.chunks(1).map(|pair| run(pair, 1)));
            let hex = |value: u32| HexOrDash(Some(value));
            log::info(format_args!(
                "math-check op={} rom={} iwram={} arm={}",
                op.name(),
                hex(check(in_rom)),
                hex(check(in_iwram)),
                HexOrDash(op.has_arm().then(|| check(arm))),
            ));

            let cost = |run: Run| {
                hw::without_interrupts(|| {
                    let started = meter::now();
                    black_box(run(&inputs, MATH_SHORT_ROUNDS));
                    let short = meter::cycles_since(started);
                    let started = meter::now();
                    black_box(run(&inputs, MATH_LONG_ROUNDS));
                    let long = meter::cycles_since(started);
                    let operations = (MATH_LONG_ROUNDS - MATH_SHORT_ROUNDS) * INPUTS as u32;
                    (long - short) * 100 / operations
                })
            };
            log::info(format_args!(
                "math-cycles-x100 op={} rom={} iwram={} arm={}",
                op.name(),
                cost(in_rom),
                cost(in_iwram),
                DecimalOrDash(op.has_arm().then(|| cost(arm))),
            ));
        }
        log_stack();
        log::info(format_args!("math done"));
        loop {
            display.wait_vblank();
        }
    }

    /// `0x%08x`, or `-` for a variant that does not exist.
    struct HexOrDash(Option<u32>);

    impl core::fmt::Display for HexOrDash {
        fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
            match self.0 {
                Some(value) => write!(f, "0x{value:08x}"),
                None => f.write_str("-"),
            }
        }
    }

    /// A number, or `-` for a variant that does not exist.
    struct DecimalOrDash(Option<u32>);

    impl core::fmt::Display for DecimalOrDash {
        fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
            match self.0 {
                Some(value) => write!(f, "{value}"),
                None => f.write_str("-"),
            }
        }
    }

    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        hw::panic_screen::show(info)
    }
}
