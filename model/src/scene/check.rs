//! The scene check: warnings, with their numbers, for scenes that load but cannot work or
//! will be slow. A scene that breaks a rule is refused when it loads ([`Scene::load`]);
//! these are the scenes that are valid and still ask the impossible of the planner: an
//! object the tool tips whenever it pushes it, a goal the tool cannot reach or the goal
//! object cannot stand in, a goal region that must first be cleared, a goal object the
//! hand cannot get behind to push it toward the goal.
//!
//! The check costs a few inverse-kinematics searches (milliseconds), so it is run by the
//! commands that start work on a scene (`plan`, `check SCENE.yaml`), not by every load.
//!
//! Frames: world frame, z up; heights are above the table top (m).

use super::{Goal, Scene};
use crate::collision::footprint::gap;
use crate::math::Pose2;
use crate::physics::Footprint;
use crate::random::SplitMix64;
use crate::robot::{IkSettings, RobotKind};
use nalgebra::Vector2;
use std::fmt;

/// Headings (yaw about the world's z) tried for the tool over the goal's centre.
pub const REACH_HEADINGS: usize = 8;

/// Inverse-kinematics attempts per heading: from the start, then from random
/// configurations within the limits.
pub const REACH_TRIES: usize = 8;

/// Points per side of the grid over the goal region's bounding square.
const REGION_GRID: usize = 41;

/// Yaws tried for the goal object at each point of the goal region.
const REGION_YAWS: usize = 16;

/// What the scene check found.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneWarning {
    /// A push that slides the object at the pushing plane's height tips it over: the tool
    /// pushes at `plane_height`, above `b / mu_g` for the lever `b` of the narrowest side
    /// (or of every side, `every_side`).
    TipsAtPlaneHeight {
        /// The object.
        object: String,
        /// Is it the goal object?
        goal_object: bool,
        /// The tool point's height above the table (m).
        plane_height: f64,
        /// The object's least lever about a footprint edge (m,
        /// [`Footprint::half_widths`]).
        half_width: f64,
        /// Its support friction.
        mu_g: f64,
        /// Is the plane above the tipping height of every side (its greatest lever)?
        every_side: bool,
    },
    /// The tool cannot be put over the goal disc's centre on the pushing plane (no
    /// inverse-kinematics solution in [`REACH_TRIES`] attempts at each of
    /// [`REACH_HEADINGS`] headings).
    GoalOutOfReach {
        /// The disc's centre (m, world xy).
        center: Vector2<f64>,
    },
    /// Part of the goal region (the disc less its margin) lies where the goal object's
    /// footprint would hang over the table's edge, whatever its yaw.
    GoalOverTableEdge {
        /// The share of the region (0-1).
        share: f64,
    },
    /// Movable objects other than the goal object start on the goal disc: where they
    /// stand, the goal object cannot (keeping `physics.object_clearance`).
    ObjectsOnGoal {
        /// The objects.
        objects: Vec<String>,
        /// The share of the goal region (0-1) where the goal object, at some yaw, stands
        /// on the table clear of every other object where it starts: zero means they must
        /// be pushed out first.
        free_share: f64,
    },
    /// The goal object starts in the goal region: the plan is the start alone.
    GoalReachedAtStart,
    /// The hand cannot stand behind the goal object to push it straight toward the goal:
    /// the tool point there (`standoff` from the object's centre, away from the goal
    /// centre: the object's bounding radius and the end effector's reach) is out of reach
    /// on the pushing plane, as [`SceneWarning::GoalOutOfReach`] tries it. The object
    /// must go sideways first, or be moved by the arm's links. On 240 held-out scenes of
    /// four arms and five designs (docs/notes/any-arm.md) the searches of such scenes
    /// were the slow ones.
    GoalObjectBehindOutOfReach {
        /// The goal object.
        object: String,
        /// The tool point behind it (m, world xy).
        point: Vector2<f64>,
        /// Its distance from the object's centre (m).
        standoff: f64,
    },
}

impl SceneWarning {
    /// Does the warning say the scene cannot work at all (rather than slowly)?
    pub fn blocks(&self) -> bool {
        match self {
            SceneWarning::TipsAtPlaneHeight {
                goal_object,
                every_side,
                ..
            } => *goal_object && *every_side,
            SceneWarning::GoalOutOfReach { .. } => true,
            SceneWarning::GoalOverTableEdge { share } => *share >= 1.0,
            SceneWarning::ObjectsOnGoal { .. }
            | SceneWarning::GoalReachedAtStart
            | SceneWarning::GoalObjectBehindOutOfReach { .. } => false,
        }
    }
}

impl fmt::Display for SceneWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneWarning::TipsAtPlaneHeight {
                object,
                goal_object,
                plane_height,
                half_width,
                mu_g,
                every_side,
            } => write!(
                f,
                "{} '{object}' tips when the tool pushes it: the pushing plane is {plane_height:.3} m \
                 above the table, above its tipping height b / mu_g = {:.3} m (b = {half_width:.3} m, \
                 its least lever about a footprint edge; mu_g = {mu_g}){}",
                if *goal_object { "the goal object" } else { "object" },
                half_width / mu_g,
                if *every_side {
                    "; it tips whichever side is pushed, so only links lower than the tool could move it \
                     (lower the plane, or give the object a wider footprint or more friction)"
                } else {
                    "; pushed on its narrow side it tips, so pushes must find its wide sides"
                }
            ),
            SceneWarning::GoalOutOfReach { center } => write!(
                f,
                "the goal disc's centre ({:.3}, {:.3}) is out of the tool's reach on the pushing \
                 plane: no joint configuration puts the tool there ({} inverse-kinematics \
                 attempts over {REACH_HEADINGS} headings); the arm cannot push the goal object in",
                center.x,
                center.y,
                REACH_TRIES * REACH_HEADINGS
            ),
            SceneWarning::GoalOverTableEdge { share } => write!(
                f,
                "{} % of the goal region (the goal disc less its margin) lies where the goal \
                 object would hang over the table's edge at any yaw{}",
                percent(*share),
                if *share >= 1.0 {
                    ": the goal cannot be reached (objects must stand wholly on the table)"
                } else {
                    ": plans must end in the rest"
                }
            ),
            SceneWarning::ObjectsOnGoal {
                objects,
                free_share,
            } => write!(
                f,
                "{} {} {} on the goal disc: the goal object can stand clear of {} in {} % of \
                 the goal region{}",
                match objects.len() {
                    1 => "object",
                    _ => "objects",
                },
                crate::input::name_list(objects.iter().map(String::as_str)),
                match objects.len() {
                    1 => "starts",
                    _ => "start",
                },
                match objects.len() {
                    1 => "it",
                    _ => "them",
                },
                percent(*free_share),
                if *free_share > 0.0 {
                    ""
                } else {
                    ", so they must be pushed out first (searches for such scenes are slower)"
                }
            ),
            SceneWarning::GoalReachedAtStart => write!(
                f,
                "the goal object starts in the goal region: the plan is the start alone"
            ),
            SceneWarning::GoalObjectBehindOutOfReach {
                object,
                point,
                standoff,
            } => write!(
                f,
                "the hand cannot get behind the goal object '{object}' to push it toward the \
                 goal: the tool point ({:.3}, {:.3}), {standoff:.3} m from its centre on the \
                 side away from the goal, is out of reach on the pushing plane ({} \
                 inverse-kinematics attempts over {REACH_HEADINGS} headings); it must be \
                 pushed sideways first or moved by the arm's links (searches for such scenes \
                 are slower)",
                point.x,
                point.y,
                REACH_TRIES * REACH_HEADINGS
            ),
        }
    }
}

/// A share (0-1) in percent for a message: a share above zero never reads as 0.
fn percent(share: f64) -> String {
    match share {
        s if s > 0.0 && s < 0.005 => "under 1".into(),
        s if s < 1.0 && s > 0.995 => "over 99".into(),
        s => format!("{:.0}", 100.0 * s),
    }
}

/// The scene check: every warning, the goal object's first.
pub fn check(scene: &Scene) -> Vec<SceneWarning> {
    let mut warnings = tipping(scene);
    if let Goal::ObjectInDisc {
        object,
        center,
        radius,
        margin,
    } = &scene.goal
    {
        if !reaches(scene, *center) {
            warnings.push(SceneWarning::GoalOutOfReach { center: *center });
        }
        let room = room_in_region(scene, *object, *center, radius - margin);
        if room.over_edge > 0.0 {
            warnings.push(SceneWarning::GoalOverTableEdge {
                share: room.over_edge,
            });
        }
        let disc = Footprint::Circle { radius: *radius };
        let at_center = Pose2::new(center.x, center.y, 0.0);
        let on_goal: Vec<String> = (scene.objects.iter().zip(&scene.start.objects))
            .enumerate()
            .filter(|(i, (o, pose))| {
                i != object && gap(&disc, &at_center, &o.footprint, pose) < 0.0
            })
            .map(|(_, (o, _))| o.name.clone())
            .collect();
        if !on_goal.is_empty() {
            warnings.push(SceneWarning::ObjectsOnGoal {
                objects: on_goal,
                free_share: room.free,
            });
        }
        if scene.goal.is_satisfied(&scene.start) {
            warnings.push(SceneWarning::GoalReachedAtStart);
        } else if let Some(behind) = behind_out_of_reach(scene, *object, *center) {
            warnings.push(behind);
        }
    }
    warnings
}

/// [`SceneWarning::GoalObjectBehindOutOfReach`] for an arm whose hand cannot stand behind
/// `object` for a push toward `center`, None otherwise (a planar hand reaches anywhere).
fn behind_out_of_reach(scene: &Scene, object: usize, center: Vector2<f64>) -> Option<SceneWarning> {
    let behind = unreachable_behind(scene, object, center)?;
    Some(SceneWarning::GoalObjectBehindOutOfReach {
        object: scene.objects[object].name.clone(),
        point: behind.point,
        standoff: behind.standoff,
    })
}

/// The tool point behind an object, away from where it must go, where the hand cannot
/// stand (world xy, m).
struct UnreachableBehind {
    point: Vector2<f64>,
    /// From the object's centre (m).
    standoff: f64,
}

/// The tool point behind `object` (at its start) for a push toward `center`, at the push
/// headings' standoff (its bounding radius and the hand's reach), if an arm cannot put its
/// tool there on the pushing plane.
fn unreachable_behind(
    scene: &Scene,
    object: usize,
    center: Vector2<f64>,
) -> Option<UnreachableBehind> {
    if scene.robot.kind != RobotKind::Arm {
        return None;
    }
    #[allow(non_snake_case)] // the object's centre in the world frame
    let p_WO = scene.start.objects[object].translation();
    let away = (p_WO - center).try_normalize(1e-9)?;
    let standoff = scene.push_standoff(object);
    let point = p_WO + away * standoff;
    (!reaches(scene, point)).then_some(UnreachableBehind { point, standoff })
}

/// Must the goal object come nearer an arm's base than it starts (the goal disc's centre
/// is nearer), from a start where the tool cannot be put over its centre on the pushing
/// plane? Then the end effector touches only the near part of it, and a push from there
/// sends it outward, farther out of reach: the scene generator draws no such goal object
/// (docs/notes/any-arm.md, "Goal objects beyond the reach"). False for a planar hand or
/// without an object goal.
pub fn goal_object_beyond_reach(scene: &Scene) -> bool {
    goal_object_and_base(scene).is_some_and(|g| {
        (g.p_WO - g.p_WBase).norm() > (g.center - g.p_WBase).norm() && !reaches(scene, g.p_WO)
    })
}

/// An arm's object goal, with where the arm and the goal object stand (world xy, m).
#[allow(non_snake_case)] // frame-named points
struct GoalObjectAndBase {
    object: usize,
    /// The goal disc's centre.
    center: Vector2<f64>,
    /// The base's origin.
    p_WBase: Vector2<f64>,
    /// The goal object's centre at the start.
    p_WO: Vector2<f64>,
}

/// [`GoalObjectAndBase`] of an arm's scene with an object goal; None otherwise.
fn goal_object_and_base(scene: &Scene) -> Option<GoalObjectAndBase> {
    let Goal::ObjectInDisc { object, center, .. } = &scene.goal else {
        return None;
    };
    (scene.robot.kind == RobotKind::Arm).then(|| GoalObjectAndBase {
        object: *object,
        center: *center,
        p_WBase: scene.robot.chain.base.translation.vector.xy(),
        p_WO: scene.start.objects[*object].translation(),
    })
}

/// How closely (m) [`reach_behind_goal_object`] brackets the hand's reach.
const REACH_PRECISION: f64 = 0.01;

/// How far the hand reaches on the pushing plane, where it cannot get behind the goal
/// object ([`SceneWarning::GoalObjectBehindOutOfReach`]): the tool point's greatest
/// distance (m) from the arm's base axis along the ray from the base through the
/// unreachable point, to `REACH_PRECISION` (1 cm), bracketed by the goal object's near side
/// (reachable, or the base itself) and that point. None where the hand gets behind it,
/// without an object goal, at the goal at the start, or for a planar hand. An arm's reach
/// on a plane is nearly a circle about its base axis (a first joint about z), so the
/// push headings use this one radius in every direction; it costs a few
/// inverse-kinematics searches, which is why only such scenes pay for it.
pub fn reach_behind_goal_object(scene: &Scene) -> Option<f64> {
    let goal = goal_object_and_base(scene)?;
    if scene.goal.is_satisfied(&scene.start) {
        return None;
    }
    let behind = unreachable_behind(scene, goal.object, goal.center)?;
    #[allow(non_snake_case)] // the base's origin in the world frame
    let p_WBase = goal.p_WBase;
    let ray = behind.point - p_WBase;
    let (mut out, direction) = (ray.norm(), ray.normalize());
    let near_side = (goal.p_WO - p_WBase).norm() - behind.standoff;
    let mut within = if near_side > 0.0 && reaches(scene, p_WBase + direction * near_side) {
        near_side
    } else {
        0.0
    };
    while out - within > REACH_PRECISION {
        let middle = 0.5 * (within + out);
        if reaches(scene, p_WBase + direction * middle) {
            within = middle;
        } else {
            out = middle;
        }
    }
    Some(within)
}

/// Objects a sliding push at the plane's height tips, the goal object first. Objects no
/// taller than the plane are passed over by the tool and left out.
fn tipping(scene: &Scene) -> Vec<SceneWarning> {
    let plane_height = scene.robot.plane.height - scene.table.top;
    let goal = scene.goal.object();
    let mut order: Vec<usize> = (0..scene.objects.len()).collect();
    order.sort_by_key(|&i| Some(i) != goal);
    order
        .into_iter()
        .filter_map(|i| {
            let o = &scene.objects[i];
            let (least, greatest) = o.footprint.half_widths();
            (o.height > plane_height && plane_height > least / o.mu_g).then(|| {
                SceneWarning::TipsAtPlaneHeight {
                    object: o.name.clone(),
                    goal_object: Some(i) == goal,
                    plane_height,
                    half_width: least,
                    mu_g: o.mu_g,
                    every_side: plane_height > greatest / o.mu_g,
                }
            })
        })
        .collect()
}

/// Can the tool be put at `center` on the pushing plane, at some heading? Damped least
/// squares from the start configuration, then from random ones within the limits (a
/// fixed seed: the same scene, the same answer).
fn reaches(scene: &Scene, center: Vector2<f64>) -> bool {
    let robot = &scene.robot;
    let mut rng = SplitMix64::new(1);
    let settings = IkSettings {
        position_tolerance: 1e-4,
        rotation_tolerance: 1e-3,
        ..IkSettings::default()
    };
    (0..REACH_TRIES).any(|attempt| {
        (0..REACH_HEADINGS).any(|h| {
            let yaw = std::f64::consts::TAU * h as f64 / REACH_HEADINGS as f64;
            let target = robot
                .plane
                .tool_pose_at(&Pose2::new(center.x, center.y, yaw));
            let seed = match attempt {
                0 => scene.start.q.clone(),
                _ => robot.chain.random_configuration(&mut rng),
            };
            robot.reach_tool_pose(&target, &seed, &settings).is_some()
        })
    })
}

/// Where the goal object can stand in the goal region: shares of a grid over it.
struct Room {
    /// Where it hangs over the table's edge at every yaw tried.
    over_edge: f64,
    /// Where, at some yaw, it stands wholly on the table and `physics.object_clearance`
    /// from every other object where it starts.
    free: f64,
}

/// [`Room`] for `object` in the disc of `radius` about `center` (a grid over it, each point
/// at [`REGION_YAWS`] yaws).
fn room_in_region(scene: &Scene, object: usize, center: Vector2<f64>, radius: f64) -> Room {
    let footprint = &scene.objects[object].footprint;
    let others: Vec<(&Footprint, &Pose2)> = (scene.objects.iter().zip(&scene.start.objects))
        .enumerate()
        .filter(|&(i, _)| i != object)
        .map(|(_, (o, pose))| (&o.footprint, pose))
        .collect();
    let clearance = scene.physics.object_clearance;
    let step = 2.0 * radius / (REGION_GRID - 1) as f64;
    let (mut inside, mut over, mut free) = (0usize, 0usize, 0usize);
    for i in 0..REGION_GRID {
        for j in 0..REGION_GRID {
            let p = center + Vector2::new(i as f64, j as f64) * step - Vector2::repeat(radius);
            if (p - center).norm() > radius {
                continue;
            }
            inside += 1;
            let poses = (0..REGION_YAWS).map(|k| {
                let yaw = std::f64::consts::TAU * k as f64 / REGION_YAWS as f64;
                Pose2::new(p.x, p.y, yaw)
            });
            let on_table: Vec<Pose2> = poses
                .filter(|pose| scene.table.holds(footprint, pose))
                .collect();
            over += usize::from(on_table.is_empty());
            free += usize::from(on_table.iter().any(|pose| {
                others
                    .iter()
                    .all(|(f, at)| gap(footprint, pose, f, at) >= clearance)
            }));
        }
    }
    let share = |n: usize| n as f64 / inside.max(1) as f64;
    Room {
        over_edge: share(over),
        free: share(free),
    }
}
