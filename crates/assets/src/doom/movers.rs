//! Doom's doors and lifts as portalcast movers, and the lines that start them as switches and
//! walk-over lines (docs/MAP_FORMAT.md, "Doom maps").
//!
//! - A **manual door** (a closed sector of one piece behind a two-sided line with a manual door
//!   special, opened by using that line) is a door the use button starts.
//! - A **remote door or lift** (a sector whose tag a line's door or lift special names) is a
//!   `locked` mover of that tag, each piece of the sector one mover of the same tag, so they
//!   start together and move as one. A door must be closed at the start (portalcast's doors
//!   start shut) and opens to 4 below the lowest ceiling round it; a lift goes down to the
//!   lowest floor round it (its own included), both as Doom's `EV_DoDoor` and `EV_DoPlat`.
//! - Its lines: a switch special on a one-sided line makes that wall a switch (showing the
//!   texture's `SW1`/`SW2` twin once used, if the IWAD has it); a walk-over special on a
//!   two-sided line makes both of its sides walk-over lines. portalcast's switches and lines
//!   all start their movers again once they rest, so Doom's once-only (`S1`, `W1`) lines act as
//!   repeatable ones.
//!
//! Speeds and waits are Doom's (35 ticks a second) in portalcast's 60: a door 2 units a Doom
//! tick (1 a portalcast tick), a blazing one 8 (5), a lift 4 (2) and a blazing one 8 (5);
//! doors wait 150 Doom ticks (257), lifts 105 (180). What does not fit (an open door's close
//! specials, a switch on a two-sided line, a map's `MOVERS_MAX` or `TRIGGERS_MAX`) goes to the
//! import report.

use std::collections::BTreeMap;

use portalcast_format::limits::{MOVERS_MAX, TRIGGERS_MAX};

use super::level::DoomLevel;

/// Doom's game ticks a second; portalcast's are 60.
pub(super) const DOOM_TICKS_PER_SECOND: u32 = 35;

/// Doom's ticks as portalcast's (60 a second), rounded.
pub(super) const fn from_doom_ticks(ticks: u32) -> u16 {
    ((ticks * 60 + DOOM_TICKS_PER_SECOND / 2) / DOOM_TICKS_PER_SECOND) as u16
}

/// How a Doom door or lift moves, in portalcast's units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Timing {
    /// World units a portalcast tick.
    pub speed: u16,
    /// portalcast ticks it stays at its far end.
    pub wait: u16,
}

/// Doom's door speed, 2 units a Doom tick (70 a second): 1 a portalcast tick (60 a second).
const DOOR_SPEED: u16 = 1;
/// Doom's blazing doors and lifts, 8 units a Doom tick (280 a second): 5 a portalcast tick.
const BLAZING_SPEED: u16 = 5;
/// Doom's lifts, 4 units a Doom tick (140 a second): 2 a portalcast tick.
const LIFT_SPEED: u16 = 2;
/// Doom's doors stay open 150 Doom ticks: 257 of portalcast's.
const DOOR_WAIT: u16 = from_doom_ticks(150);
/// Doom's lifts stay down 3 seconds (`PLATWAIT`): 180 portalcast ticks.
const LIFT_WAIT: u16 = from_doom_ticks(3 * DOOM_TICKS_PER_SECOND);
/// A door that opens for good waits as long as a portalcast door can.
const STAYS_OPEN: u16 = u16::MAX;

const fn timing(speed: u16, wait: u16) -> Timing {
    Timing { speed, wait }
}

const CLOSES: Timing = timing(DOOR_SPEED, DOOR_WAIT);
const STAYS: Timing = timing(DOOR_SPEED, STAYS_OPEN);
const BLAZING_CLOSES: Timing = timing(BLAZING_SPEED, DOOR_WAIT);
const BLAZING_STAYS: Timing = timing(BLAZING_SPEED, STAYS_OPEN);
const LIFT: Timing = timing(LIFT_SPEED, LIFT_WAIT);
const BLAZING_LIFT: Timing = timing(BLAZING_SPEED, LIFT_WAIT);

/// Doom's manual doors (opened by using the door's own line, from the side facing away from
/// it): specials 1, 26, 27 and 28 open, wait and close (the last three need a key portalcast
/// does not have: they open as plain doors); 31 to 34 open and stay; 117 and 118 are the fast
/// ("blazing") ones of each.
pub(super) const MANUAL_DOORS: [(u16, Timing); 10] = [
    (1, CLOSES),
    (26, CLOSES),
    (27, CLOSES),
    (28, CLOSES),
    (31, STAYS),
    (32, STAYS),
    (33, STAYS),
    (34, STAYS),
    (117, BLAZING_CLOSES),
    (118, BLAZING_STAYS),
];

/// How a line with a remote special starts its movers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Activation {
    /// Used (`S1`, `SR`): a switch.
    Switch,
    /// Walked over (`W1`, `WR`).
    Walk,
}

/// What a remote special does to the sectors of its tag.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Action {
    /// Opens (and closes after the wait, or stays open) a closed door.
    Door(Timing),
    /// Lowers a lift to the lowest floor round it, waits and raises it.
    Lift(Timing),
}

/// Doom's remote door specials that open (`EV_DoDoor`'s normal, open and blazing kinds) and
/// its lift specials (`EV_DoPlat`'s down-wait-up-stay), by how they are started. The close
/// specials (3, 42, 50, 75, 107, 110, 113, 116) need a door open at the start, which a
/// portalcast door is not.
const REMOTE_SPECIALS: [(u16, Activation, Action); 24] = {
    use Action::{Door, Lift};
    use Activation::{Switch, Walk};
    [
        (2, Walk, Door(STAYS)),
        (4, Walk, Door(CLOSES)),
        (10, Walk, Lift(LIFT)),
        (21, Switch, Lift(LIFT)),
        (29, Switch, Door(CLOSES)),
        (61, Switch, Door(STAYS)),
        (62, Switch, Lift(LIFT)),
        (63, Switch, Door(CLOSES)),
        (86, Walk, Door(STAYS)),
        (88, Walk, Lift(LIFT)),
        (90, Walk, Door(CLOSES)),
        (103, Switch, Door(STAYS)),
        (105, Walk, Door(BLAZING_CLOSES)),
        (106, Walk, Door(BLAZING_STAYS)),
        (108, Walk, Door(BLAZING_CLOSES)),
        (109, Walk, Door(BLAZING_STAYS)),
        (111, Switch, Door(BLAZING_CLOSES)),
        (112, Switch, Door(BLAZING_STAYS)),
        (114, Switch, Door(BLAZING_CLOSES)),
        (115, Switch, Door(BLAZING_STAYS)),
        (120, Walk, Lift(BLAZING_LIFT)),
        (121, Walk, Lift(BLAZING_LIFT)),
        (122, Switch, Lift(BLAZING_LIFT)),
        (123, Switch, Lift(BLAZING_LIFT)),
    ]
};

/// How a Doom sector moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Motion {
    /// A door: its ceiling opens from its floor up to `open`.
    Door {
        /// The open ceiling.
        open: i16,
    },
    /// A lift: its floor goes down from where it is drawn to `low`.
    Lift {
        /// The floor at the bottom.
        low: i16,
    },
}

/// A Doom sector's mover: every piece of it gets one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct SectorMover {
    /// How it moves.
    pub motion: Motion,
    /// Its speed and wait.
    pub timing: Timing,
    /// The tag whose switches and lines start it, or none for a manual door.
    pub tag: Option<u16>,
    /// Only its switches and lines start it (portalcast's `locked`): a remote mover some line
    /// here starts. One whose lines all are switches on two-sided lines, which portalcast
    /// cannot make switches, is left to the use button (facing it or standing in it).
    pub locked: bool,
}

/// What a Doom line does to the movers of its tag.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum LineTrigger {
    /// A switch on its (one-sided) wall.
    Switch {
        /// The movers' tag.
        tag: u16,
    },
    /// A walk-over line, on both of its sides.
    Walk {
        /// The movers' tag.
        tag: u16,
    },
}

/// The movers of a Doom map and the lines that start them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Movers {
    /// Each Doom sector's mover, if it moves.
    pub sectors: Vec<Option<SectorMover>>,
    /// Each linedef's trigger, if it starts movers.
    pub lines: Vec<Option<LineTrigger>>,
    /// What was left out, one line each, for the import report.
    pub left_out: Vec<String>,
}

impl Movers {
    /// The movers of `level`, whose sectors are cut into `pieces_of` pieces each.
    pub fn of(level: &DoomLevel, pieces_of: &[usize]) -> Movers {
        let mut left_out = Vec::new();
        let mut sectors = vec![None; level.sectors.len()];
        let mut movers_used = 0usize;
        for (index, slot) in sectors.iter_mut().enumerate() {
            let sector = index as u16;
            let mover = manual_door(level, sector)
                .filter(|_| pieces_of[index] == 1)
                .map(|(open, timing)| SectorMover {
                    motion: Motion::Door { open },
                    timing,
                    tag: None,
                    locked: false,
                })
                .or_else(|| remote_mover(level, sector, &mut left_out));
            let Some(mover) = mover else {
                continue;
            };
            if movers_used + pieces_of[index] > MOVERS_MAX as usize {
                left_out.push(format!(
                    "sector {index} would be a mover of {} piece(s), past the {MOVERS_MAX} movers a map holds: it stays still",
                    pieces_of[index]
                ));
                continue;
            }
            movers_used += pieces_of[index];
            *slot = Some(mover);
        }

        let moved_tags: Vec<u16> = sectors.iter().flatten().filter_map(|m| m.tag).collect();
        let mut lines = vec![None; level.linedefs.len()];
        let mut triggers_used = 0usize;
        let mut two_sided_switches: BTreeMap<u16, usize> = BTreeMap::new();
        for (index, line) in level.linedefs.iter().enumerate() {
            let Some(&(special, activation, _)) = remote_special(line.special) else {
                continue;
            };
            if line.tag == 0 || !moved_tags.contains(&line.tag) {
                continue;
            }
            let (trigger, count) = match (activation, line.two_sided()) {
                (Activation::Switch, false) => (LineTrigger::Switch { tag: line.tag }, 1),
                (Activation::Walk, true) => (LineTrigger::Walk { tag: line.tag }, 2),
                (Activation::Switch, true) => {
                    *two_sided_switches.entry(special).or_default() += 1;
                    continue;
                }
                // A walk-over special on a one-sided line: nobody crosses it, in Doom either.
                (Activation::Walk, false) => continue,
            };
            if triggers_used + count > TRIGGERS_MAX as usize {
                left_out.push(format!(
                    "linedef {index} (special {special}) is past the {TRIGGERS_MAX} switches and lines a map holds: it starts nothing"
                ));
                continue;
            }
            triggers_used += count;
            lines[index] = Some(trigger);
        }
        for (special, count) in two_sided_switches {
            left_out.push(format!(
                "special {special} is a switch on {count} two-sided line(s): portalcast's switches are solid walls, so the use button starts their movers (facing them or standing in them) unless another line does"
            ));
        }
        let started: Vec<u16> = level
            .linedefs
            .iter()
            .zip(&lines)
            .filter(|(_, trigger)| trigger.is_some())
            .map(|(line, _)| line.tag)
            .collect();
        for mover in sectors.iter_mut().flatten() {
            mover.locked = mover.tag.is_some_and(|tag| started.contains(&tag));
        }
        Movers {
            sectors,
            lines,
            left_out,
        }
    }

    /// Whether linedef `line`'s special is mapped: a manual door's (on the door's line) or a
    /// remote one that starts movers here.
    pub fn maps_special_of(&self, level: &DoomLevel, line: usize) -> bool {
        let special = level.linedefs[line].special;
        self.lines[line].is_some() || MANUAL_DOORS.iter().any(|(manual, _)| *manual == special)
    }
}

/// The remote special `special`, if it is one portalcast maps.
fn remote_special(special: u16) -> Option<&'static (u16, Activation, Action)> {
    REMOTE_SPECIALS.iter().find(|(s, _, _)| *s == special)
}

/// The door Doom's sector `sector` is, if it is a manual one: closed, behind a two-sided line
/// with a manual door special, opening (as Doom's `EV_VerticalDoor`) to 4 below the lowest
/// ceiling round it. Its open ceiling and its timing.
pub(super) fn manual_door(level: &DoomLevel, sector: u16) -> Option<(i16, Timing)> {
    let own = &level.sectors[usize::from(sector)];
    if own.floor < own.ceiling {
        return None;
    }
    let sector_of = |side: u16| level.sidedefs[usize::from(side)].sector;
    let timing = level.linedefs.iter().find_map(|line| {
        let faces_door = line.two_sided() && sector_of(line.sides[1]) == sector;
        MANUAL_DOORS
            .iter()
            .find(|(special, _)| faces_door && *special == line.special)
            .map(|&(_, timing)| timing)
    })?;
    door_open_height(level, sector).map(|open| (open, timing))
}

/// Where a door of Doom's sector `sector` opens to: 4 below the lowest ceiling round it
/// (`P_FindLowestCeilingSurrounding`), if that is above its floor.
fn door_open_height(level: &DoomLevel, sector: u16) -> Option<i16> {
    let floor = level.sectors[usize::from(sector)].floor;
    let lowest = level.neighbours(sector).map(|other| other.ceiling).min()?;
    let open = lowest.checked_sub(4)?;
    (open > floor).then_some(open)
}

/// The remote mover Doom's sector `sector` is: the action of the first line (in linedef order)
/// whose remote special names its tag, if the sector can do it. Notes in `left_out` a tagged
/// sector that cannot, or that lines of different actions name.
fn remote_mover(level: &DoomLevel, sector: u16, left_out: &mut Vec<String>) -> Option<SectorMover> {
    let own = &level.sectors[usize::from(sector)];
    if own.tag == 0 {
        return None;
    }
    let mut actions = level
        .linedefs
        .iter()
        .filter(|line| line.tag == own.tag)
        .filter_map(|line| {
            remote_special(line.special).map(|&(special, _, action)| (special, action))
        });
    let (special, action) = actions.next()?;
    if let Some((other, _)) = actions
        .find(|&(_, other)| std::mem::discriminant(&other) != std::mem::discriminant(&action))
    {
        left_out.push(format!(
            "sector {sector} is moved by specials {special} and {other}, a door's and a lift's: it is the first's"
        ));
    }
    let closed = own.floor >= own.ceiling;
    match action {
        Action::Door(timing) if closed => match door_open_height(level, sector) {
            Some(open) => Some(SectorMover {
                motion: Motion::Door { open },
                timing,
                tag: Some(own.tag),
                locked: false,
            }),
            None => {
                left_out.push(format!(
                    "sector {sector} is a door (special {special}) with no ceiling round it to open to: it stays shut"
                ));
                None
            }
        },
        Action::Door(_) => {
            left_out.push(format!(
                "sector {sector} is a door (special {special}) open at the start: portalcast's doors start shut, so it stays open"
            ));
            None
        }
        Action::Lift(timing) => {
            let low = level
                .neighbours(sector)
                .map(|other| other.floor)
                .fold(own.floor, i16::min);
            if low < own.floor && !closed {
                Some(SectorMover {
                    motion: Motion::Lift { low },
                    timing,
                    tag: Some(own.tag),
                    locked: false,
                })
            } else {
                left_out.push(format!(
                    "sector {sector} is a lift (special {special}) with no floor round it lower than its own, or closed: it stays still"
                ));
                None
            }
        }
    }
}

/// The texture a switch showing `texture` shows once used: Doom's switch textures come in
/// pairs, `SW1…` off and `SW2…` on, and a used switch swaps to its twin. The same texture where
/// `exists` says the twin is not in the WAD.
pub(super) fn thrown_switch_texture(texture: &str, exists: impl Fn(&str) -> bool) -> String {
    let twin = if let Some(rest) = texture.strip_prefix("SW1") {
        format!("SW2{rest}")
    } else if let Some(rest) = texture.strip_prefix("SW2") {
        format!("SW1{rest}")
    } else {
        return texture.to_string();
    };
    if exists(&twin) {
        twin
    } else {
        texture.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn doom_speeds_and_waits_in_portalcast_ticks() {
        assert_eq!((DOOR_WAIT, LIFT_WAIT), (257, 180));
        assert_eq!(from_doom_ticks(35), 60);
    }

    #[test]
    fn a_switch_texture_swaps_to_its_twin_if_it_exists() {
        let exists = |name: &str| name == "SW2BRN1";
        assert_eq!(thrown_switch_texture("SW1BRN1", exists), "SW2BRN1");
        assert_eq!(thrown_switch_texture("SW1GRAY", exists), "SW1GRAY");
        assert_eq!(thrown_switch_texture("STARTAN3", exists), "STARTAN3");
    }

    #[test]
    fn every_remote_special_is_listed_once() {
        let mut specials: Vec<u16> = REMOTE_SPECIALS.iter().map(|(s, _, _)| *s).collect();
        specials.sort_unstable();
        specials.dedup();
        assert_eq!(specials.len(), REMOTE_SPECIALS.len());
        assert!(specials
            .iter()
            .all(|s| MANUAL_DOORS.iter().all(|(manual, _)| manual != s)));
    }
}
