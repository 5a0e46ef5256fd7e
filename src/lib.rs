//! pushplan: whole-arm rearrangement planning by quasistatic pushing.
//!
//! The planner of King, Haustein, Srinivasa and Asfour, "Nonprehensile Whole Arm
//! Rearrangement Planning on Physics Manifolds", on its model ([`pushplan_model`], whose
//! modules this crate re-exports under the same names): planning (paths, shortcutting,
//! robustness, trajectories, plan files, DARRT, reaching, manipulation, execution), the
//! bridge to OMPL's planners in C++, and the command line.
//!
//! Units are SI throughout (m, rad, s, kg, N); the world frame has z up.

#![warn(missing_docs)]

pub mod benchmark;
pub mod bridge;
pub mod planner;
pub mod planning;
pub mod render;

// The model, under the names its modules have there.
pub use pushplan_model::{
    collision, contact, distance, error, input, limits, math, output, physics, propagate, random,
    robot, scene, semi_dynamic, state, validity,
};

pub use distance::DistanceMetric;
pub use error::{Error, Overlap, Result};
pub use math::Pose2;
pub use propagate::{Contact, Propagation, Propagator};
pub use robot::EeAction;
pub use scene::Scene;
pub use state::State;
pub use validity::Invalid;
