//! The 3D engines an execution runs in, behind one trait: the execution plays the arm's
//! links through it and reads the objects back, whatever the contact model.
//!
//! Two engines with different contact models judge every plan (issue 57): rapier
//! ([`RapierWorld`]: rigid contacts solved by impulses, objects on evenly spread feet) and
//! MuJoCo ([`MujocoWorld`]: soft contacts of a convex optimisation, objects on their own
//! faces and rims). Neither is tuned from the other's results.

use super::mujoco::MujocoWorld;
use super::rapier::{RapierWorld, SolverSettings};
use crate::math::Pose2;
use crate::robot::KinematicChain;
use crate::scene::Scene;
use nalgebra::{DVector, Isometry3, Vector3};
use std::fmt;
use std::str::FromStr;

/// Simulation step of every engine (s): 1 kHz keeps a link from moving more than a
/// millimetre per step.
pub const STEP: f64 = 0.001;

/// Which engine an execution runs in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum EngineKind {
    /// rapier: impulse-based rigid contacts; the objects stand on feet spread evenly over
    /// their footprints.
    #[default]
    Rapier,
    /// MuJoCo: soft contacts (a convex optimisation per step); the objects stand on
    /// their own geometry.
    Mujoco,
}

impl EngineKind {
    /// Every engine.
    pub const ALL: [EngineKind; 2] = [EngineKind::Rapier, EngineKind::Mujoco];

    /// The engine's name as the CLI and reports write it.
    pub fn name(self) -> &'static str {
        match self {
            EngineKind::Rapier => "rapier",
            EngineKind::Mujoco => "mujoco",
        }
    }

    /// A world of `scene`'s table, obstacles and objects (at `objects`) and the arm's
    /// links at `link_poses` (`X_WL`, one per chain link).
    pub fn world(
        self,
        scene: &Scene,
        objects: &[Pose2],
        link_poses: &[Isometry3<f64>],
        solver: &SolverSettings,
    ) -> Result<Box<dyn Engine>, String> {
        Ok(match self {
            EngineKind::Rapier => {
                Box::new(RapierWorld::with_solver(scene, objects, link_poses, solver))
            }
            EngineKind::Mujoco => Box::new(MujocoWorld::new(scene, objects, link_poses)?),
        })
    }
}

impl FromStr for EngineKind {
    type Err = String;

    fn from_str(name: &str) -> Result<Self, String> {
        crate::input::by_name(&EngineKind::ALL, EngineKind::name, "engine", name)
    }
}

impl fmt::Display for EngineKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// In reports an engine is its name.
impl serde::Serialize for EngineKind {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

/// A 3D world with the arm's links driven along given poses and free objects.
pub trait Engine {
    /// Where the arm's links are at the end of the next step (`X_WL` per chain link).
    fn move_arm(&mut self, link_poses: &[Isometry3<f64>]);

    /// Advances the world by [`STEP`] seconds.
    fn step(&mut self);

    /// Object `i`'s body pose `X_WO` (its planar frame lifted onto the table top).
    fn object_pose(&self, i: usize) -> Isometry3<f64>;

    /// Object `i` was pushed off the table.
    fn object_fell_off(&self, i: usize) -> bool;

    /// Sets object `i`'s linear velocity (m/s, world frame; it stops turning).
    fn set_object_velocity(&mut self, i: usize, v: Vector3<f64>);

    /// Object `i`'s linear velocity (m/s, world frame).
    fn object_velocity(&self, i: usize) -> Vector3<f64>;

    /// A pair of objects in contact, if any.
    fn touching_objects(&self) -> Option<(usize, usize)>;

    /// Object `i`'s planar pose (x, y and yaw of its body frame).
    fn object_pose2(&self, i: usize) -> Pose2 {
        Pose2::from_isometry(&self.object_pose(i))
    }

    /// Object `i`'s tilt: the angle between its body z axis and the world's (rad).
    fn object_tilt(&self, i: usize) -> f64 {
        let up = self.object_pose(i).rotation * Vector3::z();
        up.z.clamp(-1.0, 1.0).acos()
    }

    /// Drives the arm of `chain` through joint configurations `dt` seconds apart,
    /// interpolated linearly at the engine's rate.
    fn follow(&mut self, chain: &KinematicChain, path: &[DVector<f64>], dt: f64) {
        let per_step = (dt / STEP).round().max(1.0) as usize;
        let mut poses = Vec::new();
        for pair in path.windows(2) {
            for j in 1..=per_step {
                let f = j as f64 / per_step as f64;
                chain.forward_kinematics(&(&pair[0] * (1.0 - f) + &pair[1] * f), &mut poses);
                self.move_arm(&poses);
                self.step();
            }
        }
    }
}
