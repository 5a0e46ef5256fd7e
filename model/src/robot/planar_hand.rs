//! The free-flying planar pusher: a rigid hand that translates and turns in the pushing
//! plane. Built as the chain world -> prismatic x -> prismatic y -> revolute z -> hand.

use super::chain::{Joint, JointKind, KinematicChain, Link};
use crate::collision::Geometry;
use nalgebra::{Isometry3, Translation3, Vector3};

/// Chain of a hand whose frame sits at height `z` (m, world), translating within
/// `x_range` x `y_range` (m) and turning within [-pi, pi] rad. `geometry` is in the hand
/// frame. `max_speed` (m/s) and `max_turn_rate` (rad/s) become the joint velocity limits.
pub fn planar_hand_chain(
    z: f64,
    x_range: (f64, f64),
    y_range: (f64, f64),
    geometry: Vec<Geometry>,
    max_speed: f64,
    max_turn_rate: f64,
) -> KinematicChain {
    let joint =
        |name: &str, kind, parent, axis: Vector3<f64>, (lower, upper), max_velocity, dof| Joint {
            name: name.to_string(),
            kind,
            parent,
            origin: Isometry3::identity(),
            axis: nalgebra::Unit::new_normalize(axis),
            lower,
            upper,
            max_velocity,
            dof: Some(dof),
            held_value: 0.0,
        };
    let pi = std::f64::consts::PI;
    KinematicChain {
        links: vec![
            Link {
                name: "world".into(),
                joint: None,
                geometry: vec![],
            },
            Link {
                name: "hand_x".into(),
                joint: Some(joint(
                    "x",
                    JointKind::Prismatic,
                    0,
                    Vector3::x(),
                    x_range,
                    max_speed,
                    0,
                )),
                geometry: vec![],
            },
            Link {
                name: "hand_y".into(),
                joint: Some(joint(
                    "y",
                    JointKind::Prismatic,
                    1,
                    Vector3::y(),
                    y_range,
                    max_speed,
                    1,
                )),
                geometry: vec![],
            },
            Link {
                name: "hand".into(),
                joint: Some(joint(
                    "yaw",
                    JointKind::Revolute,
                    2,
                    Vector3::z(),
                    (-pi, pi),
                    max_turn_rate,
                    2,
                )),
                geometry,
            },
        ],
        base: Isometry3::from_parts(Translation3::new(0.0, 0.0, z), Default::default()),
        dof_links: vec![1, 2, 3],
    }
}
