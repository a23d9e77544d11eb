//! The portalcast ROM. It only builds for the GBA (`cargo rom`); a host build explains that.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "portalcast's binary is the GBA ROM: build it with `cargo rom` (writes target/portalcast.gba) \
         or run it with `cargo play`."
    );
    std::process::exit(2);
}

#[cfg(target_os = "none")]
mod rom {
    use portalcast::frame::Resolution;
    use portalcast::hw::kernels::{VramCanvas, VramPage};
    use portalcast::hw::{self, log, memory, meter, video::Display};
    use portalcast::{kernel_check, testpic};

    const KEY_SELECT: u16 = 1 << 2;
    const KEY_RIGHT: u16 = 1 << 4;
    const KEY_LEFT: u16 = 1 << 5;
    const KEY_R: u16 = 1 << 8;
    const KEY_L: u16 = 1 << 9;

    /// Entered from gba's runtime after it copied IWRAM/EWRAM and zeroed .bss.
    #[allow(unsafe_code)]
    #[no_mangle]
    extern "C" fn main() -> ! {
        hw::set_waitstates();
        meter::start();
        log::info(format_args!(
            "portalcast boot waitcnt=0x{:04x} iwram_used={} stack_room={}",
            hw::WAITCNT_SETTING,
            memory::iwram_used(),
            memory::stack_room()
        ));

        let mut resolution = Resolution::R120x80;
        let mut display = Display::start(resolution);
        display.set_palette(&testpic::PALETTE);
        if hw::keys_held() & (KEY_L | KEY_R) == KEY_L | KEY_R {
            kernel_check_scene(&mut display);
        }
        let mut phase: u32 = 0;
        let mut held_before: u16 = 0;
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

    /// L+R held at boot: draw the kernel check at every resolution with a few seeds, printing
    /// where each page is, so the emulator test can compare VRAM with the host twins.
    fn kernel_check_scene(display: &mut Display) -> ! {
        let mut seed = 1u32;
        loop {
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

    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        log::fatal(format_args!("panic: {info}"));
        loop {
            core::hint::spin_loop();
        }
    }
}
