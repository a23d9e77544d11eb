mod common;
use common::demos::replay;
use portalcast::player::collide::RADIUS;
use portalcast_format::THING_SOLID;
use portalcast_harness::KeyScript;

fn probe(name: &str, script: &KeyScript, ticks: u32) {
    let states = replay(script, 4, ticks);
    let mut closest = f64::MAX;
    let mut at = 0;
    for (tick, game) in states.iter().enumerate() {
        let map = game.map();
        let p = game.player.position;
        for thing in map.things.iter().filter(|t| t.flags & THING_SOLID != 0) {
            let dx = f64::from(p.x.to_bits() - thing.x_fx8) / 256.0;
            let dy = f64::from(p.y.to_bits() - thing.y_fx8) / 256.0;
            let gap = (dx * dx + dy * dy).sqrt() - f64::from(RADIUS + i32::from(thing.radius));
            if gap < closest {
                closest = gap;
                at = tick;
            }
        }
    }
    let last = states.last().unwrap();
    println!(
        "{name}: closest gap {closest:.2} at tick {at}; end {:?} sector {}",
        (
            f64::from(last.player.position.x.to_bits()) / 256.0,
            f64::from(last.player.position.y.to_bits()) / 256.0
        ),
        last.player.sector
    );
}

#[test]
fn probe_demos() {
    let root = portalcast_xtask::workspace_root();
    for file in ["assets/demo/tick.keys", "assets/demo/play.keys"] {
        probe(file, &KeyScript::load(&root.join(file)).unwrap(), 1000);
    }
    for (name, script, frames) in [
        ("stairs", "10-13: SELECT\n11-12: B\n20-72: UP\n100-135: RIGHT\n150-420: UP\n440-475: LEFT\n490-600: UP\n", 640),
        ("ledge", "20-45: R\n70-150: DOWN\n160-200: DOWN\n165-167: A\n", 260),
        ("crawl", "20-45: L\n70-130: DOWN\n140-200: DOWN+B\n210-240: NONE\n250-340: DOWN+B\n", 380),
        ("same", "20-80: UP\n40-70: RIGHT\n90-120: L\n100-102: A\n130-150: SELECT\n132-148: UP\n152-154: SELECT\n153: A\n160-161: START\n170-171: RIGHT\n180-181: START\n190-230: UP+B\n240-241: START\n245-246: LEFT\n250-251: START\n260-262: SELECT\n270-300: A\n", 320),
    ] {
        probe(name, &KeyScript::parse(script).unwrap(), frames);
    }
}

#[test]
fn probe_tick_counts() {
    use common::player::{distance_to_segment, solid_walls, units};
    use portalcast::player::input::Buttons;
    let root = portalcast_xtask::workspace_root();
    let script = KeyScript::load(&root.join("assets/demo/tick.keys")).unwrap();
    let states = replay(&script, 4, 916);
    let map = portalcast::render::demo::demo_map();
    let walls: Vec<((f64, f64), (f64, f64))> = solid_walls(&map).into_iter().map(|(a, b)| {
        let point = |p: portalcast::math::WorldPoint| (units(p.x.to_bits()), units(p.y.to_bits()));
        (point(a), point(b))
    }).collect();
    let (mut turns, mut strafes, mut jumps, mut slides) = (0, 0, 0, 0);
    for pair in states.windows(2) {
        let (before, after) = (&pair[0].player, &pair[1].player);
        let moved = after.position != before.position;
        let centre = (units(after.position.x.to_bits()), units(after.position.y.to_bits()));
        let touching = walls.iter().any(|&(a, b)| distance_to_segment(centre, a, b) < f64::from(RADIUS) + 1.0 / 16.0);
        turns += usize::from(after.angle != before.angle);
        strafes += usize::from(moved && pair[1].held().any(Buttons(Buttons::L.0 | Buttons::R.0)));
        jumps += usize::from(before.on_ground && !after.on_ground && !after.fly);
        slides += usize::from(moved && touching);
    }
    println!("counts: turns {turns} strafes {strafes} jumps {jumps} slides {slides}");
}
