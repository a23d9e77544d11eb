//! Buttons to intent: what the player wants to do on one tick, from the buttons held on it.
//!
//! The mapping (also the README's controls table):
//!
//! | buttons | intent |
//! |---|---|
//! | Up / Down | walk forward / back |
//! | Left / Right | turn left / right |
//! | L / R | strafe left / right |
//! | A | jump (fly mode: rise while held) |
//! | B | crouch while held (fly mode: descend while held) |
//! | Select + Up / Down | look up / down (the horizon moves; Left/Right, L/R still turn and strafe) |
//! | Select + A | re-centre the view |
//! | Select + B | run on/off |
//! | Select alone (pressed and released with no other button) | fly mode on/off |
//!
//! Select is a modifier because the GBA has ten buttons and the player needs more actions:
//! every combination here is two buttons at most and reachable with one hand on a real GBA.
//! A tap of Select toggles fly mode only when no other button was held with it, so looking
//! around (Select + Up) never toggles flying by accident. Start opens the menu; the game
//! handles it before the player sees the buttons.

/// GBA buttons as a bit set in KEYINPUT order (A = bit 0 … L = bit 9), 1 = held: the value
/// `hw::keys_held` returns and the harness's `Keys` uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Buttons(pub u16);

impl Buttons {
    /// Nothing held.
    pub const NONE: Buttons = Buttons(0);
    /// A.
    pub const A: Buttons = Buttons(1 << 0);
    /// B.
    pub const B: Buttons = Buttons(1 << 1);
    /// Select.
    pub const SELECT: Buttons = Buttons(1 << 2);
    /// Start.
    pub const START: Buttons = Buttons(1 << 3);
    /// D-pad right.
    pub const RIGHT: Buttons = Buttons(1 << 4);
    /// D-pad left.
    pub const LEFT: Buttons = Buttons(1 << 5);
    /// D-pad up.
    pub const UP: Buttons = Buttons(1 << 6);
    /// D-pad down.
    pub const DOWN: Buttons = Buttons(1 << 7);
    /// Right shoulder.
    pub const R: Buttons = Buttons(1 << 8);
    /// Left shoulder.
    pub const L: Buttons = Buttons(1 << 9);
    /// Every button.
    pub const ALL: Buttons = Buttons(0x3ff);

    /// Whether every button of `other` is held.
    pub const fn contains(self, other: Buttons) -> bool {
        self.0 & other.0 == other.0
    }

    /// Whether any button of `other` is held.
    pub const fn any(self, other: Buttons) -> bool {
        self.0 & other.0 != 0
    }

    /// The buttons held now that were not held in `before`.
    pub const fn pressed_since(self, before: Buttons) -> Buttons {
        Buttons(self.0 & !before.0)
    }

    /// The buttons held in `before` that are not held now.
    pub const fn released_since(self, before: Buttons) -> Buttons {
        Buttons(before.0 & !self.0)
    }

    /// These buttons without those of `other`.
    pub const fn without(self, other: Buttons) -> Buttons {
        Buttons(self.0 & !other.0)
    }

    /// `+1` if `plus` is held and `minus` is not, `-1` the other way round, else 0.
    const fn axis(self, plus: Buttons, minus: Buttons) -> i8 {
        (self.any(plus) as i8) - (self.any(minus) as i8)
    }
}

/// What the player wants on one tick.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Intent {
    /// `+1` forward, `-1` back.
    pub forward: i8,
    /// `+1` to the right, `-1` to the left.
    pub strafe: i8,
    /// `+1` turns right (clockwise on the top-down view, the angle grows), `-1` left.
    pub turn: i8,
    /// `+1` looks up (the horizon moves down the screen), `-1` down.
    pub look: i8,
    /// Run rather than walk.
    pub run: bool,
    /// Jump (held: a jump starts on the ground only after A was released since the last one);
    /// in fly mode, rise.
    pub jump: bool,
    /// Crouch; in fly mode, descend.
    pub crouch: bool,
    /// Put the horizon back in the middle.
    pub recentre: bool,
    /// Switch fly mode on or off.
    pub toggle_fly: bool,
    /// Use what is in front (a door, a lift, a switch): L and R pressed together.
    pub activate: bool,
}

/// Turns the buttons of successive ticks into intents: remembers the last tick's buttons for
/// presses and releases, whether Select was used as a modifier, and the run setting.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Controls {
    held: Buttons,
    /// Another button was held while Select was: its release is not a tap.
    select_chorded: bool,
    /// Run instead of walk (Select + B, or the menu).
    pub always_run: bool,
}

impl Controls {
    /// Controls with nothing held, walking.
    pub const fn new() -> Controls {
        Controls {
            held: Buttons::NONE,
            select_chorded: false,
            always_run: false,
        }
    }

    /// The intent of a tick on which `held` is held.
    pub fn read(&mut self, held: Buttons) -> Intent {
        let pressed = held.pressed_since(self.held);
        let released = held.released_since(self.held);
        self.held = held;
        let mut intent = Intent {
            turn: held.axis(Buttons::RIGHT, Buttons::LEFT),
            strafe: held.axis(Buttons::R, Buttons::L),
            ..Intent::default()
        };
        if held.contains(Buttons::SELECT) {
            if held.any(Buttons::ALL.without(Buttons::SELECT)) {
                self.select_chorded = true;
            }
            intent.look = held.axis(Buttons::UP, Buttons::DOWN);
            intent.recentre = pressed.contains(Buttons::A);
            if pressed.contains(Buttons::B) {
                self.always_run = !self.always_run;
            }
        } else {
            if released.contains(Buttons::SELECT) && !self.select_chorded {
                intent.toggle_fly = true;
            }
            self.select_chorded = false;
            intent.forward = held.axis(Buttons::UP, Buttons::DOWN);
            intent.jump = held.contains(Buttons::A);
            intent.crouch = held.contains(Buttons::B);
        }
        // L and R together: their strafes cancel, and the chord's completing press is a use.
        let shoulders = Buttons(Buttons::L.0 | Buttons::R.0);
        intent.activate = held.contains(shoulders) && pressed.any(shoulders);
        intent.run = self.always_run;
        intent
    }

    /// Follows the buttons without acting on them (while the menu is open), so that closing
    /// the menu does not turn buttons held through it into presses or a Select tap.
    pub fn observe(&mut self, held: Buttons) {
        if held.contains(Buttons::SELECT) {
            self.select_chorded = true;
        }
        self.held = held;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lone_select_tap_toggles_fly_and_a_chord_does_not() {
        let mut controls = Controls::new();
        assert!(!controls.read(Buttons::SELECT).toggle_fly);
        assert!(controls.read(Buttons::NONE).toggle_fly);
        controls.read(Buttons::SELECT);
        let look = controls.read(Buttons(Buttons::SELECT.0 | Buttons::UP.0));
        assert_eq!((look.look, look.forward), (1, 0));
        controls.read(Buttons::SELECT);
        assert!(!controls.read(Buttons::NONE).toggle_fly);
    }

    #[test]
    fn l_and_r_together_use_once_per_chord_and_do_not_strafe() {
        let mut controls = Controls::new();
        let both = Buttons(Buttons::L.0 | Buttons::R.0);
        let first = controls.read(Buttons::L);
        assert!(!first.activate && first.strafe == -1);
        let chord = controls.read(both);
        assert!(chord.activate && chord.strafe == 0);
        assert!(!controls.read(both).activate, "held, it does not repeat");
        assert!(!controls.read(Buttons::R).activate);
        assert!(controls.read(both).activate, "a new chord uses again");
    }

    #[test]
    fn select_b_toggles_run_once_per_press() {
        let mut controls = Controls::new();
        let both = Buttons(Buttons::SELECT.0 | Buttons::B.0);
        controls.read(Buttons::SELECT);
        assert!(controls.read(both).run);
        assert!(controls.read(both).run);
        controls.read(Buttons::SELECT);
        assert!(!controls.read(both).run);
    }
}
