//! A richer game on portalcast: its own map (`assets/maps/keep.map`) and sprites (a key, a
//! pedestal), a HUD of hardware sprites over the 3D view, and a bit of game logic: the key lies
//! in the hall, walking over it takes it (it leaves the map), and carried to the locked gate it
//! opens it (the gate's tag). The HUD shows `KEY 0`, `KEY 1`, then `OPEN`.
#![no_std]
#![no_main]

use gba::mmio::{OBJ_ATTR0, OBJ_ATTR1, OBJ_ATTR2, OBJ_PALETTE, OBJ_TILES};
use gba::video::obj::{ObjAttr0, ObjAttr1, ObjAttr2, ObjDisplayStyle, ObjShape};
use gba::video::{Color, Tile4};
use portalcast::hw::{log, memory, Machine, ObjVram};
use portalcast::math::Fx24_8;
use portalcast::player::{input::Controls, Player};
use portalcast::render::view::Settings;
use portalcast::text::glyph_lit;
use portalcast::world::{remove_thing, World};
use portalcast_format::MapTables;

/// The compiled assets (build.rs). A game uses what it needs of them.
#[allow(dead_code)]
mod assets {
    include!(concat!(env!("OUT_DIR"), "/assets.rs"));
}

/// The live world of the game's maps: its movers' and triggers' state (the gate).
type GameWorld =
    World<{ assets::LIVE_SECTORS }, { assets::LIVE_MOVERS }, { assets::LIVE_TRIGGERS }>;

/// The gate's tag in keep.map.
const GATE_TAG: u16 = 1;
/// How near the player's centre comes to the key to take it, in world units.
const KEY_REACH: i32 = 32;
/// The gate's middle, and how near the player carrying the key comes to it to open it.
const GATE_MIDDLE: (i32, i32) = (392, 64);
const GATE_REACH: i32 = 56;

/// The characters the HUD shows, each an 8×16 sprite of two 16-colour OBJ tiles, from tile 512
/// on: the first OBJ tile Mode 4 leaves, which `ObjVram::GameTiles` gives the game.
const HUD_CHARS: &[u8] = b" KEY01OPN";
const FIRST_TILE: u16 = 512;
/// Sprites the HUD's line takes at most: OAM entries 0.. of 128.
const HUD_SPRITES: usize = 8;

#[no_mangle]
extern "C" fn main() -> ! {
    let mut machine = Machine::start(&assets::ASSETS, ObjVram::GameTiles);
    hud_start(&mut machine);
    let map = assets::ASSETS.map("keep").expect("keep.map is compiled");
    let mut world = GameWorld::start(map);
    // The game's own copy of the things, so that a thing taken leaves the map.
    let things = memory::ewram_copy(map.things);
    let sector_things = memory::ewram_copy(map.sector_things);
    let key = things
        .iter()
        .position(|thing| assets::SPRITE_SETS[usize::from(thing.sprite)].name == "key")
        .expect("keep.map has a key");
    let key_at = (things[key].x_fx8 >> 8, things[key].y_fx8 >> 8);
    let mut player = Player::spawn(map);
    let mut controls = Controls::new();
    let (mut has_key, mut gate_open) = (false, false);
    let settings = Settings::DEFAULT;
    let mut frame = 0u32;
    loop {
        machine.ticks(|held| {
            world.tick_with_player(map, &mut player, &controls.read(held));
            let position = player.camera().position;
            let at = (position.x, position.y);
            if !has_key && near(at, key_at, KEY_REACH) {
                has_key = remove_thing(things, sector_things, key);
            }
            if has_key && !gate_open && near(at, GATE_MIDDLE, GATE_REACH) {
                world.start_tag(map, GATE_TAG);
                gate_open = true;
            }
        });
        world.show(map, machine.tick_count());
        let live = MapTables {
            things,
            sector_things,
            ..world.map(map)
        };
        machine.draw(&live, &player.camera(), &settings);
        // Right after the flip, inside VBlank: OAM changes show whole on the next frame.
        hud_show(match (has_key, gate_open) {
            (_, true) => b"OPEN",
            (true, false) => b"KEY 1",
            (false, false) => b"KEY 0",
        });
        frame += 1;
        if frame.is_multiple_of(30) {
            log::info(format_args!(
                "hud frame={frame} sector={} key={} gate={}",
                player.camera().sector,
                u8::from(has_key),
                u8::from(gate_open)
            ));
        }
    }
}

/// Whether the map point `at` (24.8) is within `reach` world units of `(x, y)`.
fn near(at: (Fx24_8, Fx24_8), (x, y): (i32, i32), reach: i32) -> bool {
    let (dx, dy) = (at.0.to_bits() / 256 - x, at.1.to_bits() / 256 - y);
    dx * dx + dy * dy <= reach * reach
}

/// The HUD's tiles (the engine's 3×5 font, doubled, white with a black shadow) and palette,
/// every sprite hidden, and the OBJ layer on with one-dimensional tile mapping. The display's
/// flips leave those DISPCNT bits alone.
fn hud_start(machine: &mut Machine) {
    OBJ_PALETTE.index(1).write(Color(0x7fff));
    OBJ_PALETTE.index(2).write(Color(0x0000));
    for (index, &character) in HUD_CHARS.iter().enumerate() {
        let first = usize::from(FIRST_TILE) + 2 * index;
        for (half, tile) in character_tiles(character).into_iter().enumerate() {
            OBJ_TILES.index(first + half).write(tile);
        }
    }
    for sprite in 0..128 {
        OBJ_ATTR0
            .index(sprite)
            .write(ObjAttr0::new().with_style(ObjDisplayStyle::NotDisplayed));
    }
    machine
        .display()
        .with_control(|control| control.with_show_obj(true).with_obj_vram_1d(true));
}

/// The two 8×8 tiles (top, bottom) of `character`'s 8×16 sprite: its glyph at twice its size
/// from pixel (1, 2), colour 1, over its shadow one pixel down and right, colour 2.
fn character_tiles(character: u8) -> [Tile4; 2] {
    let mut tiles = [[0u32; 8]; 2];
    for y in 0..16 {
        for x in 0..8 {
            let lit = |dx: usize, dy: usize| {
                x >= dx && y >= dy && glyph_lit(character, (x - dx) / 2, (y - dy) / 2)
            };
            let colour = if lit(1, 2) {
                1
            } else if lit(2, 3) {
                2
            } else {
                0
            };
            tiles[y / 8][y % 8] |= colour << (4 * x);
        }
    }
    tiles
}

/// Shows `text` in the HUD's line at the top left, 8 pixels a character.
fn hud_show(text: &[u8]) {
    for slot in 0..HUD_SPRITES {
        let character = text
            .get(slot)
            .and_then(|c| HUD_CHARS.iter().position(|known| known == c));
        let Some(index) = character else {
            OBJ_ATTR0
                .index(slot)
                .write(ObjAttr0::new().with_style(ObjDisplayStyle::NotDisplayed));
            continue;
        };
        OBJ_ATTR0
            .index(slot)
            .write(ObjAttr0::new().with_y(4).with_shape(ObjShape::Vertical));
        OBJ_ATTR1
            .index(slot)
            .write(ObjAttr1::new().with_x(4 + 8 * slot as u16));
        OBJ_ATTR2
            .index(slot)
            .write(ObjAttr2::new().with_tile_id(FIRST_TILE + 2 * index as u16));
    }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    portalcast::hw::panic_screen::show(info)
}
