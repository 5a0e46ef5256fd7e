//! The push heading: which way the tool should move, from a state, to bring an object
//! toward a target. It is what a person would do with one hand: walk round the object to
//! the side away from the target, then push it toward the target. The guided planner
//! ([`super::PlannerKind::PushKpiece`]) samples some of its controls along headings; the
//! physics decides what the push really does, so a heading only biases the search.
//!
//! All positions are world-frame xy on the table (m); headings are unit vectors.

#![allow(non_snake_case)] // frame-named points: p_WT, the tool point in the world frame

use crate::math::{closest_on_segment, Pose2};
use crate::robot::RobotKind;
use crate::scene::check::reach_behind_goal_object;
use crate::scene::{within_extent, Goal, Scene};
use crate::state::State;
use nalgebra::Vector2;

/// Within this angle (rad) of straight behind the object, seen from its centre away from
/// the goal, the tool pushes instead of walking round.
const BEHIND_HALF_ANGLE: f64 = std::f64::consts::FRAC_PI_6;

/// How much farther than the standoff (m) the tool still counts as at the object when
/// behind it (beyond it, it first closes in).
const PUSH_RANGE: f64 = 0.1;

/// How much room (m) a blocker is given beyond touching the goal object's way.
const CLEAR_BY: f64 = 0.05;

/// Where the hand cannot stand straight behind an object, the tool stands this much
/// (rad) farther round it at a time, up to a right angle (`STAND_TURNS` steps): from
/// its side, a push toward the target slides along the object and drags it along the
/// edge of the friction cone, partly toward the target.
const STAND_TURN: f64 = std::f64::consts::PI / 12.0;
const STAND_TURNS: usize = 6;

/// Where a disc blocker's radial place out of the disc will not do (off the table, on
/// another object), the places round the disc tried instead, this much (rad) farther
/// round at a time, to either side, up to half a turn (`PLACE_TURNS` steps).
const PLACE_TURN: f64 = std::f64::consts::PI / 12.0;
const PLACE_TURNS: usize = 12;

/// The geometry push headings need, fixed per scene.
#[derive(Clone, Debug)]
pub struct PushHeading {
    /// Per object: tool point to its centre when the hand stands just behind it (m,
    /// [`Scene::push_standoff`]).
    standoffs: Vec<f64>,
    /// Per object: the bounding radius of its footprint (m).
    radii: Vec<f64>,
    /// The least gap between two objects a plan keeps (m, `physics.object_clearance`).
    clearance: f64,
    /// The goal object and the disc its centre must reach, if the goal is one.
    goal: Option<GoalDisc>,
    /// Where the hand can stand to push: over the table, or nearer the arm's base than
    /// the object it pushes. None: anywhere (a free-flying hand).
    reach: Option<StandingRoom>,
}

/// Where the hand can stand behind an object (world xy, m): over the table's extent, or
/// on the arm's side of the object (beyond the table's far edges the arm runs out of
/// reach; BENCHMARKS.md, "Where dense 17 and scene 34 are hard"), and within the arm's
/// reach where that is known.
#[derive(Clone, Copy, Debug)]
struct StandingRoom {
    /// The table's extent along x and y (m).
    table_x: (f64, f64),
    table_y: (f64, f64),
    /// The arm's base.
    p_WBase: Vector2<f64>,
    /// The tool point's greatest distance from the base axis on the plane (m), measured
    /// only where the hand cannot get behind the goal object at the start
    /// ([`reach_behind_goal_object`]): there the tool stands round the side of objects
    /// it cannot get behind. None: not measured (the headings are as without it).
    reach_radius: Option<f64>,
}

impl StandingRoom {
    /// Can the hand stand at `p_WS` to push the object at `p_WO`?
    fn allows(&self, p_WS: Vector2<f64>, p_WO: Vector2<f64>) -> bool {
        let from_base = (p_WS - self.p_WBase).norm();
        (within_extent(p_WS, self.table_x, self.table_y)
            || from_base <= (p_WO - self.p_WBase).norm())
            && self.reach_radius.is_none_or(|radius| from_base <= radius)
    }

    /// Does the table hold an object of `radius` centred at `p`, inside its edges?
    fn holds(&self, p: Vector2<f64>, radius: f64) -> bool {
        (self.onto_table(p, radius) - p).norm() < 1e-12
    }

    /// `p` moved onto the table, `radius` inside its edges.
    fn onto_table(&self, p: Vector2<f64>, radius: f64) -> Vector2<f64> {
        let clamp = |v: f64, (lo, hi): (f64, f64)| {
            if lo + radius <= hi - radius {
                v.clamp(lo + radius, hi - radius)
            } else {
                0.5 * (lo + hi)
            }
        };
        Vector2::new(clamp(p.x, self.table_x), clamp(p.y, self.table_y))
    }
}

/// Where the goal object's centre must end: within `radius` of `center` (the disc less
/// its margin).
#[derive(Clone, Copy, Debug)]
struct GoalDisc {
    object: usize,
    center: Vector2<f64>,
    radius: f64,
}

/// The goal object's way in a state: from its centre `p_WO` straight to the goal
/// centre, `route` (world xy, m).
struct Way {
    goal: GoalDisc,
    p_WO: Vector2<f64>,
    route: Vector2<f64>,
}

impl Way {
    /// How far `p` (world xy) is from the straight way (m).
    fn corridor_distance(&self, p: Vector2<f64>) -> f64 {
        (p - closest_on_segment(p, self.p_WO, self.goal.center)).norm()
    }

    /// The way's unit normal (to its left), None when the goal object is at the goal
    /// centre (a way of no length).
    fn normal(&self) -> Option<Vector2<f64>> {
        (self.route.norm_squared() >= 1e-12)
            .then(|| Vector2::new(-self.route.y, self.route.x).normalize())
    }
}

/// Where a blocker stands in the goal object's way.
enum InTheWay {
    /// In the goal disc's reach, `from_center` off the disc's centre.
    Disc { from_center: Vector2<f64> },
    /// In the corridor of the straight way, `side` off its nearest point `p_WC`.
    Corridor {
        p_WC: Vector2<f64>,
        side: Vector2<f64>,
    },
}

/// A push worth trying: `object` toward `target` (world xy, m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PushTarget {
    /// The object to push.
    pub object: usize,
    /// Where to (world xy, m).
    pub target: Vector2<f64>,
}

impl PushHeading {
    /// The push headings of `scene` (its goal object and disc, its table and obstacles).
    pub fn new(scene: &Scene) -> PushHeading {
        let goal = match &scene.goal {
            Goal::ObjectInDisc {
                object,
                center,
                radius,
                margin,
            } => Some(GoalDisc {
                object: *object,
                center: *center,
                radius: radius - margin,
            }),
            _ => None,
        };
        PushHeading {
            standoffs: (0..scene.objects.len())
                .map(|i| scene.push_standoff(i))
                .collect(),
            radii: scene.objects.iter().map(|o| o.bounding_radius).collect(),
            clearance: scene.physics.object_clearance,
            goal,
            reach: match scene.robot.kind {
                RobotKind::Arm => Some(StandingRoom {
                    table_x: scene.table.x,
                    table_y: scene.table.y,
                    p_WBase: scene.robot.chain.base.translation.vector.xy(),
                    reach_radius: reach_behind_goal_object(scene),
                }),
                RobotKind::PlanarHand => None,
            },
        }
    }

    /// The objects in the goal object's way, each with a place out of it. An object the
    /// goal object could touch anywhere in the goal disc goes radially out of the disc's
    /// reach, or sideways off the corridor below when radially out is in it
    /// (`sideways_out_of_the_way`), or, where the hand has an arm and that place is off
    /// the table, on another object or a push it cannot make, round the disc to the
    /// nearest place that is none of these (`place_round_the_disc`). An object the goal
    /// object would touch on the straight line to the goal centre (that corridor) goes
    /// sideways off the line, to the side it stands on unless the hand could not stand
    /// behind it for that push (beyond the table's edge, farther from the arm's base than
    /// the object): then across the line, onto the table. Empty without an object goal.
    pub fn blockers(&self, state: &State) -> Vec<PushTarget> {
        let mut blockers = Vec::new();
        self.for_each_blocker(&state.objects, |way, object, in_the_way, _| {
            let target = match in_the_way {
                InTheWay::Disc { from_center } => {
                    self.out_of_the_disc(state, way, object, from_center)
                }
                InTheWay::Corridor { p_WC, side } => {
                    self.off_the_line(state, way, object, p_WC, side)
                }
            };
            blockers.push(PushTarget { object, target });
        });
        blockers
    }

    /// How far the objects in the goal object's way ([`Self::blockers`]) reach into it,
    /// summed (m): each into the disc's reach, or into the corridor the goal object sweeps
    /// on the straight line to the goal centre. Zero when the way is clear.
    pub fn blockage(&self, objects: &[Pose2]) -> f64 {
        let mut sum = 0.0;
        self.for_each_blocker(objects, |_, _, _, depth| sum += depth);
        sum
    }

    /// Tool point to the centre of `object` (m) when the hand stands just behind it.
    fn standoff(&self, object: usize) -> f64 {
        self.standoffs[object]
    }

    /// Can the hand stand behind `object`, at `p_WB`, to push it along the unit `push`?
    fn can_push_along(
        &self,
        room: &StandingRoom,
        object: usize,
        p_WB: Vector2<f64>,
        push: Vector2<f64>,
    ) -> bool {
        room.allows(p_WB - push * self.standoff(object), p_WB)
    }

    /// Centre distance (m) at which the goal object and `object` never touch.
    fn apart(&self, goal: &GoalDisc, object: usize) -> f64 {
        self.radii[goal.object] + self.radii[object] + self.clearance
    }

    /// Calls `f` with the goal object's way, each blocker, where it stands in the way and
    /// how deep (m). Only where the blockers are: their places out of the way are
    /// [`Self::blockers`]' (the blockage, in every projected state, needs none).
    fn for_each_blocker(&self, objects: &[Pose2], mut f: impl FnMut(&Way, usize, InTheWay, f64)) {
        let Some(goal) = self.goal else {
            return;
        };
        let p_WO = objects[goal.object].translation();
        let way = Way {
            goal,
            p_WO,
            route: goal.center - p_WO,
        };
        let route = way.route;
        for (object, pose) in objects.iter().enumerate() {
            if object == goal.object {
                continue;
            }
            let p_WB = pose.translation();
            let apart = self.apart(&goal, object);
            let from_center = p_WB - goal.center;
            let disc_reach = goal.radius + apart;
            if from_center.norm() < disc_reach {
                let depth = disc_reach - from_center.norm();
                f(&way, object, InTheWay::Disc { from_center }, depth);
                continue;
            }
            // Along the route: the nearest point of the segment, ahead of the goal object.
            let length2 = route.norm_squared();
            if length2 < 1e-12 {
                continue;
            }
            let t = ((p_WB - p_WO).dot(&route) / length2).min(1.0);
            if t <= 0.0 {
                continue;
            }
            let p_WC = p_WO + route * t;
            let side = p_WB - p_WC;
            if side.norm() < apart {
                f(
                    &way,
                    object,
                    InTheWay::Corridor { p_WC, side },
                    apart - side.norm(),
                );
            }
        }
    }

    /// A place for a blocker in the goal disc's reach, `from_center` off its centre:
    /// radially out of the reach, unless that is in the corridor (then sideways off it),
    /// off the table, on another object or a push the hand cannot make: then the first
    /// place round the disc, nearest the radial one, where none of these is so.
    fn out_of_the_disc(
        &self,
        state: &State,
        way: &Way,
        object: usize,
        from_center: Vector2<f64>,
    ) -> Vector2<f64> {
        let goal = &way.goal;
        let apart = self.apart(goal, object);
        let out = from_center.try_normalize(1e-9).unwrap_or(Vector2::x());
        let radial = goal.center + out * (goal.radius + apart + CLEAR_BY);
        let in_the_way = way.corridor_distance(radial) < apart;
        let sideways = in_the_way
            .then(|| self.sideways_out_of_the_way(state, way, object))
            .flatten();
        sideways
            .or_else(|| self.place_round_the_disc(state, way, object, out))
            .unwrap_or(radial)
    }

    /// The first place for a disc blocker round the disc, out of its reach by
    /// [`CLEAR_BY`], from the radial one along `out` (unit) turned by [`PLACE_TURN`] steps
    /// to either side, up to half a turn: on the table, off the corridor, clear of the
    /// other objects, and a push the hand can stand behind. None without an arm (a
    /// free-flying hand needs no such care) or where there is no such place.
    fn place_round_the_disc(
        &self,
        state: &State,
        way: &Way,
        object: usize,
        out: Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        let room = self.reach?;
        let goal = &way.goal;
        let apart = self.apart(goal, object);
        let distance = goal.radius + apart + CLEAR_BY;
        let p_WB = state.objects[object].translation();
        turned_both_ways(out, PLACE_TURN, PLACE_TURNS, 1.0)
            .map(|direction| goal.center + direction * distance)
            .find(|&p| {
                room.holds(p, self.radii[object])
                    && way.corridor_distance(p) >= apart + CLEAR_BY
                    && self.is_clear(state, way, object, p)
                    && (p - p_WB)
                        .try_normalize(1e-9)
                        .is_some_and(|push| self.can_push_along(&room, object, p_WB, push))
            })
    }

    /// Is `p` (world xy) a place for `object` clear of every object but itself and the
    /// goal object (which moves on), by the clearance a plan keeps?
    fn is_clear(&self, state: &State, way: &Way, object: usize, p: Vector2<f64>) -> bool {
        state.objects.iter().enumerate().all(|(other, pose)| {
            other == object
                || other == way.goal.object
                || (pose.translation() - p).norm()
                    >= self.radii[object] + self.radii[other] + self.clearance
        })
    }

    /// A place for a blocker `side` off the straight line's nearest point `p_WC`: sideways
    /// off the line, to the side it stands on unless the hand cannot stand behind it for
    /// that push: then across the way, staying on the table.
    fn off_the_line(
        &self,
        state: &State,
        way: &Way,
        object: usize,
        p_WC: Vector2<f64>,
        side: Vector2<f64>,
    ) -> Vector2<f64> {
        let apart = self.apart(&way.goal, object);
        // A corridor blocker has a way of some length to stand in: the normal is there.
        let out = side
            .try_normalize(1e-9)
            .or_else(|| way.normal())
            .unwrap_or(Vector2::x());
        let off = out * (apart + CLEAR_BY);
        let Some(room) = self.reach else {
            return p_WC + off;
        };
        let p_WB = state.objects[object].translation();
        if !self.can_push_along(&room, object, p_WB, out)
            && self.can_push_along(&room, object, p_WB, -out)
        {
            return room.onto_table(p_WC - off, self.radii[object]);
        }
        p_WC + off
    }

    /// For a disc blocker whose radial place is in the corridor (radially out of the disc
    /// is straight into the way when the blocker stands between the disc and the goal
    /// object): the nearest place straight sideways off the corridor and out of the disc's
    /// reach, in 1 cm steps up to 0.6 m, on the table, clear of the other objects, on its
    /// own side first and where the hand can stand behind it for the push. None: a place
    /// round the disc, or the radial one (also without an arm: a free-flying hand needs no
    /// such care).
    fn sideways_out_of_the_way(
        &self,
        state: &State,
        way: &Way,
        object: usize,
    ) -> Option<Vector2<f64>> {
        let room = self.reach?;
        let normal = way.normal()?;
        let goal = &way.goal;
        let r = self.radii[object];
        let apart = self.apart(goal, object);
        let disc_reach = goal.radius + apart;
        let p_WB = state.objects[object].translation();
        let own = if (p_WB - way.p_WO).dot(&normal) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        let clear = |p: Vector2<f64>| {
            (p - goal.center).norm() >= disc_reach + CLEAR_BY
                && way.corridor_distance(p) >= apart + CLEAR_BY
                && self.is_clear(state, way, object, p)
        };
        [own, -own]
            .into_iter()
            .map(|sign| normal * sign)
            .filter(|&out| self.can_push_along(&room, object, p_WB, out))
            .filter_map(|out| {
                (1..=60)
                    .map(|step| p_WB + out * (0.01 * step as f64))
                    .find(|&p| clear(p))
            })
            .find(|&p| room.holds(p, r))
    }

    /// The unit heading for the tool at `p_WT` (world xy) to push `object` toward
    /// `p_WG` (world xy), or `None` when the object is already there.
    pub fn heading(
        &self,
        state: &State,
        p_WT: Vector2<f64>,
        object: usize,
        p_WG: Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        let standoff = self.standoff(object);
        let p_WO = state.objects[object].translation();
        // d: the way the object should go.
        let d = (p_WG - p_WO).try_normalize(1e-9)?;
        let from_object = p_WT - p_WO;
        let distance = from_object.norm();
        let stand = self.stand(object, p_WO, d, from_object);
        let cos_stand = if distance > 1e-9 {
            from_object.dot(&stand) / distance
        } else {
            1.0
        };
        let is_there = cos_stand >= BEHIND_HALF_ANGLE.cos();
        if is_there && distance <= standoff + PUSH_RANGE {
            // Push: halfway between through the object's centre (no turning) and toward
            // the target (corrects a tool that stands off the line; from the side, it
            // slides along the object and drags it).
            return (-from_object.normalize() + d)
                .try_normalize(1e-9)
                .or(Some(d));
        }
        if !is_there && distance < standoff + PUSH_RANGE {
            // Walk round, on the shorter side, keeping the standoff: the tangent turning
            // toward `stand`, pulled outward while nearer than the standoff.
            let outward = from_object / distance.max(1e-9);
            let left = Vector2::new(-outward.y, outward.x);
            let tangent = if left.dot(&stand) >= 0.0 { left } else { -left };
            let push_out = ((standoff - distance) / standoff).max(0.0);
            return (tangent + outward * push_out).try_normalize(1e-9);
        }
        // Away from the object: straight to where it stands.
        (p_WO + stand * standoff - p_WT).try_normalize(1e-9)
    }

    /// Which way from `object`'s centre `p_WO` (unit, world xy) the tool stands to push it
    /// along `d`: straight behind it, or, where the hand's reach is known and ends short
    /// of that, turned round by [`STAND_TURN`] steps, on the tool's side first, to the
    /// first place it reaches (up to its side; none: straight behind).
    fn stand(
        &self,
        object: usize,
        p_WO: Vector2<f64>,
        d: Vector2<f64>,
        from_object: Vector2<f64>,
    ) -> Vector2<f64> {
        let behind = -d;
        let Some(room) = self.reach.filter(|room| room.reach_radius.is_some()) else {
            return behind;
        };
        let left = Vector2::new(-behind.y, behind.x);
        let own = if from_object.dot(&left) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        let standoff = self.standoff(object);
        turned_both_ways(behind, STAND_TURN, STAND_TURNS, own)
            .find(|&stand| room.allows(p_WO + stand * standoff, p_WO))
            .unwrap_or(behind)
    }
}

/// The unit `v`, then turned by `step` (rad) at a time to either side up to `turns` steps,
/// nearest first: `first` (1: counter-clockwise, -1: clockwise) before the other side.
fn turned_both_ways(
    v: Vector2<f64>,
    step: f64,
    turns: usize,
    first: f64,
) -> impl Iterator<Item = Vector2<f64>> {
    let left = Vector2::new(-v.y, v.x);
    std::iter::once(0.0)
        .chain((1..=turns).flat_map(move |turn| {
            let angle = first * step * turn as f64;
            [angle, -angle]
        }))
        .map(move |angle| v * angle.cos() + left * angle.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Objects of radius 0.05 m, the first the goal object, its disc (less margin) of
    /// 0.1 m at `center`; clearance 0.01 m: apart 0.11 m.
    fn goal_in_disc(
        tool_reach: f64,
        objects: usize,
        center: Vector2<f64>,
        reach: Option<StandingRoom>,
    ) -> PushHeading {
        PushHeading {
            standoffs: vec![0.05 + tool_reach; objects],
            radii: vec![0.05; objects],
            clearance: 0.01,
            goal: Some(GoalDisc {
                object: 0,
                center,
                radius: 0.1,
            }),
            reach,
        }
    }

    fn heading_at(object: Vector2<f64>, tool: Vector2<f64>) -> Vector2<f64> {
        let h = PushHeading {
            standoffs: vec![0.1],
            radii: vec![0.05],
            clearance: 0.01,
            goal: None,
            reach: None,
        };
        let state = State::from_flat(&[0.0, object.x, object.y, 0.0], 1);
        h.heading(&state, tool, 0, Vector2::new(1.0, 0.0)).unwrap()
    }

    #[test]
    fn behind_the_object_it_pushes_toward_the_goal() {
        let h = heading_at(Vector2::new(0.5, 0.0), Vector2::new(0.4, 0.0));
        assert!((h - Vector2::new(1.0, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn far_away_it_heads_for_the_point_behind_the_object() {
        // The point behind is (0.4, 0): from (0.4, 0.5) straight down.
        let h = heading_at(Vector2::new(0.5, 0.0), Vector2::new(0.4, 0.5));
        assert!((h - Vector2::new(0.0, -1.0)).norm() < 1e-12);
    }

    #[test]
    fn in_front_of_the_object_it_walks_round_not_through() {
        // The tool between the object and the goal: moving along the tangent, never
        // toward the object.
        let object = Vector2::new(0.5, 0.0);
        let tool = Vector2::new(0.6, 0.01);
        let h = heading_at(object, tool);
        assert!(h.dot(&(object - tool)) <= 1e-9, "{h}");
        assert!(h.y > 0.9, "goes round on the side it stands on: {h}");
    }

    #[test]
    fn blockers_are_the_objects_in_the_goal_disc_or_on_the_route_and_go_out_of_reach() {
        // The goal object at the origin, the goal disc (less margin) of 0.1 m at (1, 0);
        // all radii 0.05, clearance 0.01: apart = 0.11.
        let h = goal_in_disc(0.15, 4, Vector2::new(1.0, 0.0), None);
        let state = State::from_flat(
            &[
                0.0, // one joint
                0.0, 0.0, 0.0, // the goal object
                1.05, 0.1, 0.0, // in the disc's reach (0.21): goes radially out
                0.5, -0.05, 0.0, // on the route: goes sideways, to -y
                -0.05, 0.0, 0.0, // behind the goal object: not in the way
            ],
            1,
        );
        let blockers = h.blockers(&state);
        assert_eq!(blockers.len(), 2, "{blockers:?}");
        let disc = blockers[0];
        assert_eq!(disc.object, 1);
        let out = disc.target - Vector2::new(1.0, 0.0);
        assert!((out.norm() - 0.26).abs() < 1e-12);
        assert!((out.normalize() - Vector2::new(0.05, 0.1).normalize()).norm() < 1e-12);
        let route = blockers[1];
        assert_eq!(route.object, 2);
        assert!((route.target - Vector2::new(0.5, -0.16)).norm() < 1e-12);
        // Depths: the disc's reach 0.21 less 0.05^2 + 0.1^2 under the root; the corridor's
        // half-width 0.11 less 0.05.
        let disc_depth = 0.21 - (0.05f64.powi(2) + 0.1f64.powi(2)).sqrt();
        assert!((h.blockage(&state.objects) - (disc_depth + 0.06)).abs() < 1e-12);
    }
    #[test]
    fn a_blocker_the_hand_cannot_get_behind_goes_across_the_way_onto_the_table() {
        // A table over x 0.3..1.0 m, y -0.9..0.9 m, the arm's base at the origin. The goal
        // object's way runs along x = 0.9, 0.1 m inside the far edge, from (0.9, 0.5) to
        // the disc at (0.9, -0.3). Radii 0.05, clearance 0.01: apart 0.11; the hand
        // stands 0.05 + 0.1 behind a blocker.
        let room = StandingRoom {
            table_x: (0.3, 1.0),
            table_y: (-0.9, 0.9),
            p_WBase: Vector2::zeros(),
            reach_radius: None,
        };
        let h = goal_in_disc(0.1, 3, Vector2::new(0.9, -0.3), Some(room));
        let state = State::from_flat(
            &[
                0.0, // one joint
                0.9, 0.5, 0.0, // the goal object
                // 2 cm inside the way: pushed further inside, the hand would stand at
                // (1.03, 0.2), beyond the far edge and farther from the base than the
                // blocker. It goes across, to x = 0.9 + 0.16, held 0.05 inside the edge.
                0.88, 0.2, 0.0,
                // 6 cm inside: the hand stands at (0.99, 0), over the table. Inside, to
                // x = 0.9 - 0.16.
                0.84, 0.0, 0.0,
            ],
            1,
        );
        let blockers = h.blockers(&state);
        assert_eq!(blockers.len(), 2, "{blockers:?}");
        assert_eq!(blockers[0].object, 1);
        assert!(
            (blockers[0].target - Vector2::new(0.95, 0.2)).norm() < 1e-12,
            "{blockers:?}"
        );
        assert_eq!(blockers[1].object, 2);
        assert!(
            (blockers[1].target - Vector2::new(0.74, 0.0)).norm() < 1e-12,
            "{blockers:?}"
        );
    }
    #[test]
    fn a_disc_blocker_whose_radial_place_is_in_the_way_goes_sideways_off_it() {
        // The goal object at (0, 1), the disc (less margin) of 0.1 m at the origin: the
        // way runs down x = 0. Radii 0.05, clearance 0.01: apart 0.11, the disc's reach
        // 0.21. A blocker at (0, 0.15) is in the disc's reach; radially out, (0, 0.26),
        // is the middle of the way. Sideways (+x first: its own side is ambiguous and
        // counts as +x), out of the disc's reach by CLEAR_BY: x >= sqrt(0.26^2 - 0.15^2)
        // = 0.212, the first 1 cm step 0.22, also 0.22 off the way (>= 0.16).
        let room = StandingRoom {
            table_x: (-1.0, 1.0),
            table_y: (-1.0, 2.0),
            p_WBase: Vector2::new(-2.0, 0.0),
            reach_radius: None,
        };
        let h = goal_in_disc(0.1, 2, Vector2::zeros(), Some(room));
        let state = State::from_flat(&[0.0, 0.0, 1.0, 0.0, 0.0, 0.15, 0.0], 1);
        let blockers = h.blockers(&state);
        assert_eq!(blockers.len(), 1, "{blockers:?}");
        assert!(
            (blockers[0].target - Vector2::new(0.22, 0.15)).norm() < 1e-12,
            "{blockers:?}"
        );
        // Without an arm (no standing room), the radial place stays.
        let free = PushHeading { reach: None, ..h };
        assert!((free.blockers(&state)[0].target - Vector2::new(0.0, 0.26)).norm() < 1e-12);
    }

    #[test]
    fn a_disc_blocker_whose_radial_place_is_off_the_table_or_taken_goes_round_the_disc() {
        // A table over x 0.3..1.0 m, y -0.9..0.9 m, the arm's base at the origin. Radii
        // 0.05, clearance 0.01: apart 0.11; places round the disc 0.1 + 0.11 + 0.05 = 0.26
        // from its centre; the hand stands 0.05 + 0.1 behind a blocker.
        let room = StandingRoom {
            table_x: (0.3, 1.0),
            table_y: (-0.9, 0.9),
            p_WBase: Vector2::zeros(),
            reach_radius: None,
        };
        // The disc at the far edge, (0.9, -0.3); the goal object comes from (0.5, 0.3). A
        // blocker at (0.95, -0.3) would go radially to (1.16, -0.3), over the edge. Turned
        // 15-75 degrees its place is still beyond x = 0.95 (the edge less its radius);
        // turned 90 degrees toward +y, (0.9, -0.04) is 0.144 m from the way (less than
        // 0.16); toward -y, (0.9, -0.56) is on the table, off the way and clear, and the
        // hand stands behind it at (0.978, -0.153), over the table.
        let h = goal_in_disc(0.1, 2, Vector2::new(0.9, -0.3), Some(room));
        let state = State::from_flat(&[0.0, 0.5, 0.3, 0.0, 0.95, -0.3, 0.0], 1);
        let blockers = h.blockers(&state);
        assert_eq!(blockers.len(), 1, "{blockers:?}");
        assert!(
            (blockers[0].target - Vector2::new(0.9, -0.56)).norm() < 1e-12,
            "{blockers:?}"
        );
        // Without an arm (no standing room), the radial place stays.
        let free = PushHeading { reach: None, ..h };
        assert!((free.blockers(&state)[0].target - Vector2::new(1.16, -0.3)).norm() < 1e-12);

        // The disc at (0.6, -0.3), the goal object coming down x = 0.6 from (0.6, 0.4). A
        // blocker at (0.6, -0.35) goes radially to (0.6, -0.56), where a third object
        // stands; turned 15 degrees either way its place is 0.068 m from that object's
        // centre (less than 0.11); turned 30 degrees toward +x, (0.73, -0.525), is clear.
        let h = goal_in_disc(0.1, 3, Vector2::new(0.6, -0.3), Some(room));
        let state = State::from_flat(&[0.0, 0.6, 0.4, 0.0, 0.6, -0.35, 0.0, 0.6, -0.56, 0.0], 1);
        let blockers = h.blockers(&state);
        assert_eq!(blockers.len(), 1, "{blockers:?}");
        let turned = 30f64.to_radians();
        let place = Vector2::new(0.6 + 0.26 * turned.sin(), -0.3 - 0.26 * turned.cos());
        assert!((blockers[0].target - place).norm() < 1e-12, "{blockers:?}");
        let from_third = (place - Vector2::new(0.6, -0.56)).norm();
        assert!(from_third >= 0.11, "{from_third}");
    }

    #[test]
    fn where_the_hand_cannot_get_behind_it_stands_round_the_side_and_pushes_inward() {
        // The arm's base at the origin, its reach 0.95 m; the goal object (radius 0.05, the
        // hand's reach 0.05: standoff 0.1) at (0.9, 0) must go to (0.5, 0). Straight behind,
        // (1.0, 0), is out of reach, and so are the places turned 15-60 degrees round
        // (0.997, 0.988, 0.973, 0.954 m from the base); turned 75 degrees, (0.926, 0.097) is
        // 0.931 m out: there the tool stands, on the side (+y) it comes from.
        let room = |reach| StandingRoom {
            table_x: (0.3, 1.2),
            table_y: (-1.0, 1.0),
            p_WBase: Vector2::zeros(),
            reach_radius: reach,
        };
        let state = State::from_flat(&[0.0, 0.9, 0.0, 0.0], 1);
        let (object, goal) = (Vector2::new(0.9, 0.0), Vector2::new(0.5, 0.0));
        let turned = 75f64.to_radians();
        let stand = object + Vector2::new(turned.cos(), turned.sin()) * 0.1;
        assert!((stand.norm() - 0.931).abs() < 1e-3);
        let h = goal_in_disc(0.05, 1, goal, Some(room(Some(0.95))));
        let far = Vector2::new(0.9, 0.3);
        let to_stand = h.heading(&state, far, 0, goal).unwrap();
        assert!(
            (to_stand - (stand - far).normalize()).norm() < 1e-12,
            "{to_stand}"
        );
        // There, the push: halfway between through the centre and toward the goal, so
        // inward (toward the base and the goal) and into the object.
        let push = h.heading(&state, stand, 0, goal).unwrap();
        let into = (object - stand).normalize();
        assert!((push - (into + (goal - object).normalize()).normalize()).norm() < 1e-12);
        assert!(push.x < -0.7 && push.dot(&into) > 0.7, "{push}");
        // Where the reach is not measured (the hand gets behind the goal object at the
        // start), or where it allows straight behind, the tool heads for (1.0, 0).
        for reach in [None, Some(1.1)] {
            let h = goal_in_disc(0.05, 1, goal, Some(room(reach)));
            let to_behind = h.heading(&state, far, 0, goal).unwrap();
            let behind = Vector2::new(1.0, 0.0);
            assert!((to_behind - (behind - far).normalize()).norm() < 1e-12);
        }
    }
}
