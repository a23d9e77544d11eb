//! The thesis' scene preprocessing (its §3.4, [`Preprocessing::On`](super::view::Preprocessing)):
//! the visits of a sector seen through several neighbouring portals, merged into one.
//!
//! A first pass walks the portals as the drawing walk does but draws nothing: it records every
//! visit (a sector, its columns, the visit whose portal led there) in a [`VisitPlan`], and
//! merges a visit into the sector's latest group when their columns touch (the thesis'
//! "connectable" test, `entry.x2 == x1`, either way round). A second pass draws each group once,
//! over all of its columns.
//!
//! The order of the second pass differs from the thesis' on purpose. The thesis drew its list in
//! order, each new sector inserted right after the sector whose portal led to it; but a group
//! can then come before one of its members' parents (a sector reached first through one
//! neighbour and later, in other columns, through a sector the list put after it), and a
//! sector drawn before the sector in front of it draws over the wrong clip windows. Here a group
//! is drawn only once the groups of all its members' parents are: front to back in every column
//! (in one column the visits form one chain from the eye, so two groups that share a column are
//! never ready together). If the groups' dependencies ever form a cycle, the groups left are
//! drawn visit by visit in walk order, which is always front to back.

use super::walk::VISITS_TRACKED;

/// Most visits one frame's plan holds; a frame with more is drawn by the plain walk.
pub const MAX_VISITS: usize = 512;

/// No visit or group (an empty link).
const NONE: u16 = u16::MAX;

/// One visit of the first pass.
#[derive(Clone, Copy)]
struct Visit {
    /// The visit's own columns, `[first, end)`.
    first: i16,
    end: i16,
    /// The group the visit belongs to.
    group: u16,
    /// The first of the visits this one leads to, then their siblings in turn.
    first_child: u16,
    next_sibling: u16,
    /// The next visit of the same group.
    next_member: u16,
}

/// Visits of one sector whose columns form one run, drawn together.
#[derive(Clone, Copy)]
struct Group {
    sector: u16,
    first: i16,
    end: i16,
    first_member: u16,
    last_member: u16,
    /// Members whose parent's group is not drawn yet.
    waiting: u16,
    drawn: bool,
}

const NO_VISIT: Visit = Visit {
    first: 0,
    end: 0,
    group: NONE,
    first_child: NONE,
    next_sibling: NONE,
    next_member: NONE,
};

const NO_GROUP: Group = Group {
    sector: NONE,
    first: 0,
    end: 0,
    first_member: NONE,
    last_member: NONE,
    waiting: 0,
    drawn: false,
};

/// Where the second pass is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Phase {
    /// Nothing drawn yet.
    Start,
    /// Drawing ready groups.
    Groups,
    /// A dependency cycle was met: drawing the visits of undrawn groups in walk order, from
    /// this visit on.
    Fallback(u16),
}

/// One frame's visits and their groups, and the second pass's progress through them.
pub struct VisitPlan {
    visits: [Visit; MAX_VISITS],
    groups: [Group; MAX_VISITS],
    visit_count: u16,
    group_count: u16,
    /// Each sector's latest group. Not cleared between frames: an entry counts only if it names
    /// a group of this frame that holds that sector.
    latest_group: [u16; VISITS_TRACKED],
    /// Groups ready to draw (their parents' groups all drawn).
    ready: [u16; MAX_VISITS],
    ready_count: u16,
    phase: Phase,
    /// Groups drawn whole by a dependency cycle's fallback, visit by visit.
    cycles: u16,
}

/// A plan with no room for another visit ([`MAX_VISITS`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlanFull;

/// A visit of the plan, for [`VisitPlan::record`]'s `parent`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VisitId(u16);

impl Default for VisitPlan {
    fn default() -> Self {
        VisitPlan::new()
    }
}

impl VisitPlan {
    /// An empty plan.
    pub const fn new() -> VisitPlan {
        VisitPlan {
            visits: [NO_VISIT; MAX_VISITS],
            groups: [NO_GROUP; MAX_VISITS],
            visit_count: 0,
            group_count: 0,
            latest_group: [NONE; VISITS_TRACKED],
            ready: [NONE; MAX_VISITS],
            ready_count: 0,
            phase: Phase::Start,
            cycles: 0,
        }
    }

    /// Empties the plan for a new frame.
    pub fn clear(&mut self) {
        self.visit_count = 0;
        self.group_count = 0;
        self.ready_count = 0;
        self.phase = Phase::Start;
        self.cycles = 0;
    }

    /// Visits recorded.
    pub fn visit_count(&self) -> u32 {
        u32::from(self.visit_count)
    }

    /// Groups the visits form: what the second pass draws (unless a cycle splits some).
    pub fn group_count(&self) -> u32 {
        u32::from(self.group_count)
    }

    /// Groups the second pass had to draw visit by visit (a dependency cycle).
    pub fn split_groups(&self) -> u32 {
        u32::from(self.cycles)
    }

    /// Records a visit of `sector` in columns `[first, end)`, led to by `parent`'s portal
    /// (`None` for the eye's sector), merging it into the sector's latest group if their
    /// columns touch. [`PlanFull`] when the plan is full.
    pub fn record(
        &mut self,
        sector: u16,
        first: i32,
        end: i32,
        parent: Option<VisitId>,
    ) -> Result<VisitId, PlanFull> {
        let index = self.visit_count;
        if usize::from(index) == MAX_VISITS {
            return Err(PlanFull);
        }
        let (first, end) = (first as i16, end as i16);
        let parent = parent.map_or(NONE, |VisitId(parent)| parent);
        let mut visit = Visit {
            first,
            end,
            ..NO_VISIT
        };
        if parent != NONE {
            let parent_visit = &mut self.visits[usize::from(parent)];
            visit.next_sibling = parent_visit.first_child;
            parent_visit.first_child = index;
        }
        let waiting = u16::from(parent != NONE);
        let latest = self.latest_group.get(usize::from(sector)).copied();
        let joined = latest.filter(|&group| {
            group < self.group_count && {
                let group = &self.groups[usize::from(group)];
                group.sector == sector && (group.end == first || group.first == end)
            }
        });
        if let Some(group_index) = joined {
            let group = &mut self.groups[usize::from(group_index)];
            group.first = group.first.min(first);
            group.end = group.end.max(end);
            group.waiting += waiting;
            let last = group.last_member;
            group.last_member = index;
            self.visits[usize::from(last)].next_member = index;
            visit.group = group_index;
        } else {
            let group_index = self.group_count;
            self.groups[usize::from(group_index)] = Group {
                sector,
                first,
                end,
                first_member: index,
                last_member: index,
                waiting,
                drawn: false,
            };
            self.group_count += 1;
            if let Some(slot) = self.latest_group.get_mut(usize::from(sector)) {
                *slot = group_index;
            }
            visit.group = group_index;
        }
        self.visits[usize::from(index)] = visit;
        self.visit_count += 1;
        Ok(VisitId(index))
    }

    /// The second pass's next draw: a sector and its columns `[first, end)`, each returned only
    /// after everything in front of it in those columns was. The caller draws each before
    /// asking for the next.
    pub fn next_draw(&mut self) -> Option<(u16, i32, i32)> {
        if self.phase == Phase::Start {
            self.phase = Phase::Groups;
            self.push_ready_roots();
        }
        if self.phase == Phase::Groups {
            if let Some(group) = self.pop_ready() {
                self.release_children(group);
                let group = &self.groups[usize::from(group)];
                return Some((group.sector, i32::from(group.first), i32::from(group.end)));
            }
            self.phase = Phase::Fallback(0);
        }
        let Phase::Fallback(mut next) = self.phase else {
            return None;
        };
        // Every group left waits on another left: a cycle. A visit's parent comes before it in
        // walk order, and is either drawn already (with its group) or drawn here before it.
        let mut draw = None;
        while draw.is_none() && next < self.visit_count {
            let visit = self.visits[usize::from(next)];
            let group = &self.groups[usize::from(visit.group)];
            if !group.drawn {
                if group.first_member == next {
                    self.cycles += 1;
                }
                draw = Some((group.sector, i32::from(visit.first), i32::from(visit.end)));
            }
            next += 1;
        }
        self.phase = Phase::Fallback(next);
        draw
    }

    fn push_ready_roots(&mut self) {
        for index in 0..self.group_count {
            let group = &self.groups[usize::from(index)];
            if group.waiting == 0 && !group.drawn {
                self.ready[usize::from(self.ready_count)] = index;
                self.ready_count += 1;
            }
        }
    }

    fn pop_ready(&mut self) -> Option<u16> {
        let count = self.ready_count.checked_sub(1)?;
        self.ready_count = count;
        Some(self.ready[usize::from(count)])
    }

    /// Marks `group` drawn and makes ready every group whose last waiting member it leads to.
    fn release_children(&mut self, group: u16) {
        self.groups[usize::from(group)].drawn = true;
        let mut member = self.groups[usize::from(group)].first_member;
        while member != NONE {
            let mut child = self.visits[usize::from(member)].first_child;
            while child != NONE {
                let child_group = self.visits[usize::from(child)].group;
                let waiting = &mut self.groups[usize::from(child_group)].waiting;
                *waiting -= 1;
                if *waiting == 0 {
                    self.ready[usize::from(self.ready_count)] = child_group;
                    self.ready_count += 1;
                }
                child = self.visits[usize::from(child)].next_sibling;
            }
            member = self.visits[usize::from(member)].next_member;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::vec::Vec;

    /// A visit of a generated walk: its sector, columns and depth, in walk order.
    #[derive(Clone, Debug)]
    struct Walked {
        sector: u16,
        first: i32,
        end: i32,
        parent: Option<usize>,
    }

    /// A walk as the renderer's could be: children split their parent's columns into disjoint
    /// runs, and no sector is seen twice along one column (a ray crosses a convex sector once).
    fn walk_from(choices: &[u16], sectors: u16, width: i32) -> Vec<Walked> {
        let mut walked = vec![Walked {
            sector: 0,
            first: 0,
            end: width,
            parent: None,
        }];
        let mut choice = choices.iter().copied().cycle();
        let mut stack = vec![0usize];
        while let Some(at) = stack.pop() {
            if walked.len() >= 200 {
                break;
            }
            let (first, end) = (walked[at].first, walked[at].end);
            let mut ancestors = Vec::new();
            let mut up = Some(at);
            while let Some(index) = up {
                ancestors.push(walked[index].sector);
                up = walked[index].parent;
            }
            let mut column = first;
            let mut children = Vec::new();
            while column < end {
                let pick = choice.next().unwrap_or(0);
                let width = 1 + i32::from(pick % 7);
                let stop = (column + width).min(end);
                let sector = pick % sectors;
                if pick % 3 != 0 && !ancestors.contains(&sector) {
                    children.push(Walked {
                        sector,
                        first: column,
                        end: stop,
                        parent: Some(at),
                    });
                }
                column = stop;
            }
            // Depth first, in wall order: the children are pushed so the first pops first,
            // and get their indices when they are visited.
            for child in children.into_iter().rev() {
                walked.push(child);
                stack.push(walked.len() - 1);
            }
        }
        // Renumber into walk (preorder) order.
        preorder(&walked)
    }

    fn preorder(walked: &[Walked]) -> Vec<Walked> {
        let mut order = Vec::new();
        let mut stack = vec![0usize];
        while let Some(at) = stack.pop() {
            order.push(at);
            let mut children: Vec<usize> = (0..walked.len())
                .filter(|&child| walked[child].parent == Some(at))
                .collect();
            children.sort_by_key(|&child| walked[child].first);
            stack.extend(children.into_iter().rev());
        }
        let new_index = |old: usize| order.iter().position(|&o| o == old).unwrap();
        order
            .iter()
            .map(|&old| Walked {
                parent: walked[old].parent.map(new_index),
                ..walked[old].clone()
            })
            .collect()
    }

    /// A walk written as `(sector, first, end, parent)` tuples, in walk order.
    fn walk_of(visits: &[(u16, i32, i32, Option<usize>)]) -> Vec<Walked> {
        visits
            .iter()
            .map(|&(sector, first, end, parent)| Walked {
                sector,
                first,
                end,
                parent,
            })
            .collect()
    }

    fn plan_of(walked: &[Walked]) -> Box<VisitPlan> {
        let mut plan = Box::new(VisitPlan::new());
        let mut ids = Vec::new();
        for visit in walked {
            let parent = visit.parent.map(|parent| ids[parent]);
            ids.push(
                plan.record(visit.sector, visit.first, visit.end, parent)
                    .unwrap(),
            );
        }
        plan
    }

    fn draws(plan: &mut VisitPlan) -> Vec<(u16, i32, i32)> {
        core::iter::from_fn(|| plan.next_draw()).collect()
    }

    /// In every column, the draws that cover it are the walk's visits of that column, in the
    /// walk's (front to back) order.
    fn assert_front_to_back(walked: &[Walked], drawn: &[(u16, i32, i32)], width: i32) {
        for column in 0..width {
            let walk: Vec<u16> = walked
                .iter()
                .filter(|v| (v.first..v.end).contains(&column))
                .map(|v| v.sector)
                .collect();
            let draw: Vec<u16> = drawn
                .iter()
                .filter(|(_, first, end)| (*first..*end).contains(&column))
                .map(|(sector, _, _)| *sector)
                .collect();
            assert_eq!(walk, draw, "column {column}: {drawn:?}");
        }
    }

    proptest! {
        #[test]
        fn every_column_is_drawn_front_to_back(
            choices in proptest::collection::vec(any::<u16>(), 1..64),
            sectors in 2u16..12,
        ) {
            let width = 120;
            let walked = walk_from(&choices, sectors, width);
            let mut plan = plan_of(&walked);
            let drawn = draws(&mut plan);
            assert_front_to_back(&walked, &drawn, width);
            prop_assert!(drawn.len() <= walked.len());
            prop_assert_eq!(plan.visit_count() as usize, walked.len());
        }
    }

    #[test]
    fn touching_visits_of_a_sector_merge_into_one_draw() {
        // The eye's sector 0 sees sector 1 through two neighbouring portals, and sector 2
        // behind each of those.
        let walked = walk_of(&[
            (0, 0, 100, None),
            (1, 0, 40, Some(0)),
            (2, 10, 40, Some(1)),
            (1, 40, 70, Some(0)),
            (2, 40, 60, Some(3)),
        ]);
        let mut plan = plan_of(&walked);
        assert_eq!(plan.group_count(), 3);
        assert_eq!(draws(&mut plan), [(0, 0, 100), (1, 0, 70), (2, 10, 60)]);
        assert_eq!(plan.split_groups(), 0);
    }

    /// The thesis' pass 2 order (its Listing 3.5): one entry per sector, each new sector
    /// inserted right after the sector whose portal first led to it, drawn in list order over
    /// its merged columns.
    fn thesis_order(walked: &[Walked]) -> Vec<(u16, i32, i32)> {
        let mut list: Vec<(u16, i32, i32)> = Vec::new();
        for visit in walked {
            if let Some(entry) = list.iter_mut().find(|entry| entry.0 == visit.sector) {
                entry.1 = entry.1.min(visit.first);
                entry.2 = entry.2.max(visit.end);
                continue;
            }
            let at = visit.parent.map_or(0, |parent| {
                1 + list
                    .iter()
                    .position(|entry| entry.0 == walked[parent].sector)
                    .unwrap()
            });
            list.insert(at, (visit.sector, visit.first, visit.end));
        }
        list
    }

    #[test]
    fn a_group_waits_for_every_member_s_parent() {
        // Sector 4 is seen through sector 3 (columns 50..60) and then through the second visit
        // of sector 1 (60..65), which the eye's sector 0 reaches through sector 5. The thesis'
        // list puts sector 4 (inserted after 3) before sector 1 (inserted earlier, after 0, and
        // pushed back by 3's insertion), so it would draw 4 in columns 60..65 before the sector
        // in front of it there.
        let walked = walk_of(&[
            (0, 0, 100, None),
            (1, 0, 20, Some(0)),
            (2, 5, 15, Some(1)),
            (3, 40, 60, Some(0)),
            (4, 50, 60, Some(3)),
            (5, 60, 80, Some(0)),
            (1, 60, 70, Some(5)),
            (4, 60, 65, Some(6)),
        ]);
        let thesis = thesis_order(&walked);
        let thesis_result =
            std::panic::catch_unwind(|| assert_front_to_back(&walked, &thesis, 100));
        assert!(thesis_result.is_err(), "the thesis' order: {thesis:?}");
        let mut plan = plan_of(&walked);
        let drawn = draws(&mut plan);
        assert_front_to_back(&walked, &drawn, 100);
        assert_eq!(drawn.len(), 7, "{drawn:?}");
        assert_eq!(plan.split_groups(), 0);
    }

    #[test]
    fn a_dependency_cycle_falls_back_to_walk_order() {
        // Sector 1 behind sector 2 in 0..10, sector 2 behind sector 1 in 10..20 (possible only
        // for non-convex arrangements, but the plan must not lose a column if it happens): each
        // merged group would wait on the other.
        let walked = walk_of(&[
            (0, 0, 20, None),
            (2, 0, 10, Some(0)),
            (1, 0, 10, Some(1)),
            (1, 10, 20, Some(0)),
            (2, 10, 20, Some(3)),
        ]);
        let mut plan = plan_of(&walked);
        assert_eq!(plan.group_count(), 3);
        let drawn = draws(&mut plan);
        assert_front_to_back(&walked, &drawn, 20);
        assert_eq!(plan.split_groups(), 2);
        assert_eq!(drawn.len(), 5);
    }

    #[test]
    fn a_full_plan_refuses_the_next_visit() {
        let mut plan = Box::new(VisitPlan::new());
        let root = plan.record(0, 0, 240, None).ok();
        for index in 1..MAX_VISITS {
            let column = (index % 240) as i32;
            assert!(plan
                .record(1 + index as u16, column, column + 1, root)
                .is_ok());
        }
        assert_eq!(plan.record(9, 0, 1, root), Err(PlanFull));
        plan.clear();
        assert_eq!(plan.visit_count(), 0);
        assert!(plan.record(0, 0, 240, None).is_ok());
    }
}
