//! The game: the player on one of the shipped maps, the quality settings and the Start menu,
//! advanced one tick per VBlank from the buttons held on it.
//!
//! Everything here is a function of the sequence of buttons, one set per tick: the ROM runs
//! [`Game::tick`] for each VBlank's sample and draws what [`Game::camera`] sees, and the host
//! runs the same code on the same sequence (a harness key script) to predict what the ROM
//! shows.

use portalcast_format::MapTables;

use crate::demo::DEMO_MAP;
use crate::menu::{self, Entry, Menu, MenuText, Shown, ENTRIES};
use portalcast::player::input::{Buttons, Controls};
use portalcast::player::Player;
use portalcast::render::light::Lighting;
use portalcast::render::view::{Camera, Settings};
use portalcast::render::view::{Floors, TexturePlacement};
use portalcast::world::World;

/// The live state of the ROM's maps: room for the largest one with movers.
pub type GameWorld = World<
    { crate::assets::LIVE_SECTORS },
    { crate::assets::LIVE_MOVERS },
    { crate::assets::LIVE_TRIGGERS },
>;

/// The state of a game.
///
/// Laid out in declaration order, the player first: the ROM keeps one game at a fixed address,
/// so the tick's code reaches the player's fields as offsets from that address, and halfword and
/// signed-byte loads and stores take offsets below 256 in one instruction. Left to the compiler's
/// order, a field added to the settings put the player 1,132 bytes in, and the tick cost 49
/// cycles more (`cargo bench-tick`).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub struct Game<'m> {
    /// The player.
    pub player: Player,
    maps: &'m [MapTables<'m>],
    map_index: usize,
    /// Buttons to intent, with the run setting.
    pub controls: Controls,
    /// The Start menu.
    pub menu: Menu,
    /// Quality settings.
    pub settings: Settings,
    /// The heads-up display (frame rate and cycles) is shown.
    pub hud: bool,
    /// The map's moving sectors.
    pub world: GameWorld,
    held: Buttons,
    ticks: u32,
}

impl<'m> Game<'m> {
    /// A game on the demo map (or the first of `maps`), at 120×80 with lighting, the player at
    /// the map's start.
    pub fn new(maps: &'m [MapTables<'m>]) -> Game<'m> {
        let mut game = Game::blank(maps);
        game.start();
        game
    }

    /// The game before [`Game::start`]: no world, the player nowhere in particular. A constant,
    /// so that the ROM can write it where it keeps the game without a copy on the stack.
    pub const fn blank(maps: &'m [MapTables<'m>]) -> Game<'m> {
        Game {
            maps,
            map_index: 0,
            player: Player::NOWHERE,
            world: World::new(),
            controls: Controls::new(),
            menu: Menu {
                open: false,
                cursor: 0,
            },
            settings: Settings::DEFAULT,
            hud: false,
            held: Buttons::NONE,
            ticks: 0,
        }
    }

    /// Plays `maps` (from the next [`Game::start`]).
    pub fn set_maps(&mut self, maps: &'m [MapTables<'m>]) {
        self.maps = maps;
    }

    /// Starts the game in place: on the demo map (or the first), the player at its start.
    pub fn start(&mut self) {
        let maps = self.maps;
        self.map_index = maps
            .iter()
            .position(|map| map.name == DEMO_MAP)
            .unwrap_or(0);
        self.player = Player::spawn(&maps[self.map_index]);
        self.world.restart(&maps[self.map_index]);
    }

    /// The map being played, as it is now (its moving sectors' live heights).
    pub fn map(&self) -> MapTables<'_> {
        self.world.map(&self.maps[self.map_index])
    }

    /// Sets the light of the map's glowing, strobing and flickering sectors for a frame drawn
    /// now, at this tick ([`World::show`]): run before [`Game::map`] is drawn.
    pub fn show(&mut self) {
        self.world.show(&self.maps[self.map_index], self.ticks);
    }

    /// The name of the map being played.
    pub fn map_name(&self) -> &'m str {
        self.maps[self.map_index].name
    }

    /// Ticks run so far.
    pub fn ticks(&self) -> u32 {
        self.ticks
    }

    /// The buttons of the last tick.
    pub fn held(&self) -> Buttons {
        self.held
    }

    /// What the view shows.
    pub fn camera(&self) -> Camera {
        self.player.camera()
    }

    /// The values the menu shows.
    pub fn shown(&self) -> Shown<'m> {
        Shown {
            resolution: self.settings.resolution,
            lighting: self.settings.lighting,
            map: self.maps[self.map_index].name,
            fly: self.player.fly,
            run: self.controls.always_run,
            hud: self.hud,
            textures: self.settings.textures,
            preprocessing: self.settings.preprocessing,
            floors: self.settings.floors,
            things: self.settings.things,
        }
    }

    /// The menu's text, if it is open.
    pub fn menu_text(&self) -> Option<MenuText> {
        self.menu
            .open
            .then(|| menu::text(self.menu.cursor, &self.shown()))
    }

    /// One tick with `held` held: the menu if it is open (the game is paused), else the player.
    pub fn tick(&mut self, held: Buttons) {
        let pressed = held.pressed_since(self.held);
        self.held = held;
        self.ticks = self.ticks.wrapping_add(1);
        if self.menu.open {
            self.controls.observe(held);
            self.menu_keys(pressed);
        } else if pressed.contains(Buttons::START) {
            self.menu.open = true;
            self.controls.observe(held);
        } else {
            let intent = self.controls.read(held);
            // By reference: a copy of the tables' slices costs every tick.
            let maps = self.maps;
            let map = &maps[self.map_index];
            if map.movers.is_empty() && map.triggers.is_empty() {
                self.player.tick(&intent, map);
            } else {
                self.world.tick_with_player(map, &mut self.player, &intent);
            }
        }
    }

    fn menu_keys(&mut self, pressed: Buttons) {
        let count = ENTRIES.len();
        if pressed.any(Buttons(Buttons::START.0 | Buttons::B.0)) {
            self.menu.open = false;
        } else if pressed.contains(Buttons::UP) {
            self.menu.cursor = (self.menu.cursor + count - 1) % count;
        } else if pressed.contains(Buttons::DOWN) {
            self.menu.cursor = (self.menu.cursor + 1) % count;
        } else if pressed.any(Buttons(Buttons::RIGHT.0 | Buttons::A.0)) {
            self.change(ENTRIES[self.menu.cursor], true);
        } else if pressed.contains(Buttons::LEFT) {
            self.change(ENTRIES[self.menu.cursor], false);
        }
    }

    /// Moves `entry`'s value to the next (or previous) one.
    fn change(&mut self, entry: Entry, forward: bool) {
        match entry {
            Entry::Resolution => {
                let steps = if forward { 1 } else { 2 };
                for _ in 0..steps {
                    self.settings.resolution = self.settings.resolution.next();
                }
                // Half-width floors exist only at 240 wide: elsewhere the setting says full,
                // as the pixels are.
                if !Floors::offered_at(self.settings.resolution) {
                    self.settings.floors = Floors::Full;
                }
            }
            Entry::Lighting => {
                const CYCLE: [Lighting; 3] =
                    [Lighting::SectorDepth, Lighting::Off, Lighting::Sector];
                let at = CYCLE
                    .iter()
                    .position(|&l| l == self.settings.lighting)
                    .unwrap_or(0);
                let next = if forward {
                    at + 1
                } else {
                    at + CYCLE.len() - 1
                };
                self.settings.lighting = CYCLE[next % CYCLE.len()];
            }
            Entry::Map => {
                let count = self.maps.len();
                self.map_index = if forward {
                    (self.map_index + 1) % count
                } else {
                    (self.map_index + count - 1) % count
                };
                self.player = Player::spawn(&self.maps[self.map_index]);
                self.world.restart(&self.maps[self.map_index]);
            }
            Entry::Fly => self.player.toggle_fly(),
            Entry::Run => self.controls.always_run = !self.controls.always_run,
            Entry::Preprocessing => {
                self.settings.preprocessing = self.settings.preprocessing.next();
            }
            Entry::Floors => {
                if Floors::offered_at(self.settings.resolution) {
                    self.settings.floors = self.settings.floors.next();
                }
            }
            Entry::Hud => self.hud = !self.hud,
            Entry::Things => self.settings.things = self.settings.things.next(),
            Entry::Textures => {
                self.settings.textures = match self.settings.textures {
                    TexturePlacement::Ewram => TexturePlacement::Rom,
                    TexturePlacement::Rom => TexturePlacement::Ewram,
                }
            }
        }
    }
}
