//! The smallest game on portalcast: one room, walked with the D-pad (L and R strafe, A jumps;
//! docs/GUIDE.md builds it step by step).
#![no_std]
#![no_main]

use portalcast::prelude::*;

/// The compiled assets: `ASSETS`, and each table on its own (build.rs). A game uses what it
/// needs of them.
#[allow(dead_code)]
mod assets {
    include!(concat!(env!("OUT_DIR"), "/assets.rs"));
}

#[no_mangle]
extern "C" fn main() -> ! {
    let mut machine = Machine::start(&assets::ASSETS, ObjVram::Engine);
    let map = &assets::MAPS[0];
    let mut player = Player::spawn(map);
    let mut controls = Controls::new();
    let settings = Settings::DEFAULT;
    let mut frame = 0u32;
    loop {
        machine.ticks(|held| player.tick(&controls.read(held), map));
        let stats = machine.draw(map, &player.camera(), &settings);
        frame += 1;
        if frame.is_multiple_of(60) {
            let camera = player.camera();
            log::info(format_args!(
                "game frame={frame} x={} y={} sector={} columns={}",
                camera.position.x.to_bits(),
                camera.position.y.to_bits(),
                camera.sector,
                stats.wall_columns
            ));
        }
    }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    portalcast::hw::panic_screen::show(info)
}
