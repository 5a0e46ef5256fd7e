//! Caging an object: where the tool must be for the hand to hold an object, and an arm
//! configuration that puts it there.

use super::PrimitiveFailure;
use crate::collision::query::signed_distance;
use crate::math::Pose2;
use crate::robot::IkSettings;
use crate::state::State;
use crate::validity::{check_objects, check_state};
use crate::Scene;
use nalgebra::{Vector2, Vector3};

/// Gap between the hand and a caged object when the hand closes in (m).
pub const CAGE_CLEARANCE: f64 = 1e-3;

/// Approach directions tried, relative to the direction of the push (rad): straight
/// behind the object first, then from the sides (a cage holds from any side).
const APPROACH_TURNS: [f64; 5] = [0.0, 0.6, -0.6, 1.2, -1.2];

/// A hand holding one object: the object's planar pose in the tool's planar frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cage {
    /// The object held.
    pub object: usize,
    /// The object's pose (x, y in m, yaw in rad) in the frame of the tool's planar pose.
    pub grip: Pose2,
}

impl Cage {
    /// The cage of `object` as it is in `state`: the object's pose relative to the tool.
    pub fn of_state(scene: &Scene, state: &State, object: usize) -> Cage {
        let robot = &scene.robot;
        let tool = robot
            .plane
            .planar_pose(&robot.tool_pose(&robot.link_poses(&state.q)));
        Cage {
            object,
            grip: tool.inverse().compose(&state.objects[object]),
        }
    }

    /// The tool's planar pose that holds the object at `object_pose`.
    pub fn tool_for(&self, object_pose: &Pose2) -> Pose2 {
        object_pose.compose(&self.grip.inverse())
    }
}

/// The unit direction (tool planar frame) in which the hand points: its approach axis
/// (the tool's z axis) seen from above, or its x axis if that points straight down.
fn approach_axis(scene: &Scene) -> Vector2<f64> {
    let orientation = scene.robot.plane.orientation;
    let z = orientation * Vector3::z();
    let axis = if z.xy().norm() > 0.1 {
        z.xy()
    } else {
        (orientation * Vector3::x()).xy()
    };
    axis.normalize()
}

/// How far in front of the tool (along `axis`, m) the object at relative yaw `yaw` sits
/// when the hand touches it with [`CAGE_CLEARANCE`]; `None` if no distance up to the
/// two bounding radii clears it.
fn grip_distance(scene: &Scene, object: usize, axis: Vector2<f64>, yaw: f64) -> Option<f64> {
    let robot = &scene.robot;
    let hand = &robot.chain.links[robot.ee_link].geometry;
    let item = &scene.objects[object];
    // Tool at the origin with yaw 0; the hand link's pose follows from the tool offset.
    let hand_pose = robot.plane.tool_pose_at(&Pose2::new(0.0, 0.0, 0.0)) * robot.tool.inverse();
    let clear = |d: f64| {
        let object_pose = Pose2::new(d * axis.x, d * axis.y, yaw).to_isometry(scene.table.top);
        hand.iter().all(|g| {
            signed_distance(g, &hand_pose, &item.geometry, &object_pose, CAGE_CLEARANCE)
                .is_none_or(|gap| gap >= CAGE_CLEARANCE)
        })
    };
    let reach: f64 = hand
        .iter()
        .map(|g| g.shape.compute_local_bounding_sphere().radius + g.local.translation.vector.norm())
        .fold(0.0, f64::max);
    let (mut near, mut far) = (0.0, reach + item.bounding_radius + CAGE_CLEARANCE);
    if !clear(far) {
        return None;
    }
    if clear(near) {
        return Some(near);
    }
    for _ in 0..30 {
        let mid = 0.5 * (near + far);
        if clear(mid) {
            far = mid;
        } else {
            near = mid;
        }
    }
    Some(far)
}

/// The first step of a Push: an arm configuration whose hand cages `object` where it is
/// in `state`, ready to carry it to `target`. The hand approaches from behind the push
/// direction if it can, else from the side. `Err` if the target is no place for the
/// object (off the table or overlapping) or no approach reaches a valid state.
pub fn approach(
    scene: &Scene,
    state: &State,
    object: usize,
    target: &Pose2,
) -> Result<State, PrimitiveFailure> {
    let mut placed = state.objects.clone();
    placed[object] = *target;
    check_objects(scene, &placed, |i| i == object)?;

    let robot = &scene.robot;
    let axis = approach_axis(scene);
    let from = state.objects[object];
    let push = target.translation() - from.translation();
    let heading = if push.norm() > 1e-9 {
        push.y.atan2(push.x)
    } else {
        from.theta
    };
    let settings = IkSettings::default();
    let mut last = PrimitiveFailure::Unreachable;
    for turn in APPROACH_TURNS {
        // Tool yaw that points the approach axis along the push (turned by `turn`).
        let yaw = heading + turn - axis.y.atan2(axis.x);
        let relative_yaw = from.theta - yaw;
        let Some(d) = grip_distance(scene, object, axis, relative_yaw) else {
            continue;
        };
        let cage = Cage {
            object,
            grip: Pose2::new(d * axis.x, d * axis.y, relative_yaw),
        };
        let tool = robot.plane.tool_pose_at(&cage.tool_for(&from));
        for seed in [&state.q, &scene.start.q] {
            let Some(q) = robot.reach_tool_pose(&tool, seed, &settings) else {
                continue;
            };
            let caged = State {
                q,
                objects: state.objects.clone(),
            };
            match check_state(scene, &caged) {
                Ok(()) => return Ok(caged),
                Err(reason) => last = PrimitiveFailure::Invalid(reason),
            }
        }
    }
    Err(last)
}
