//! pushplan's model: everything the planner knows of the world, with no planner in it.
//!
//! The model behind the planner of King, Haustein, Srinivasa and Asfour, "Nonprehensile
//! Whole Arm Rearrangement Planning on Physics Manifolds", built and tested without OMPL,
//! a C++ compiler or cxx (the `pushplan` crate puts OMPL's planners on top of it):
//!
//! - [`scene`]: scene files (YAML) and their validated form, with the clearances objects keep;
//! - [`robot`]: robots from URDF (and the planar hand), kinematics, inverse kinematics,
//!   Workspace Goal Regions, the constraint projection of actions onto the pushing plane;
//! - [`collision`]: shapes and geometric queries; [`contact`]: arm-object contacts;
//! - [`physics`]: quasistatic planar pushing (limit surface, friction, complementarity,
//!   tipping); [`semi_dynamic`]: the workshop paper's rigid-body transition function;
//! - [`propagate`] (`ConstrainedProp`, Alg. 2), [`validity`] and [`distance`] (the metric);
//! - [`state`], [`math`], [`random`], [`input`], [`output`], [`limits`] and [`error`]:
//!   what they all share.
//!
//! Units are SI throughout (m, rad, s, kg, N); the world frame has z up.

#![warn(missing_docs)]

pub mod collision;
pub mod contact;
pub mod distance;
pub mod error;
pub mod input;
pub mod limits;
pub mod math;
pub mod output;
pub mod physics;
pub mod propagate;
pub mod random;
pub mod robot;
pub mod scene;
pub mod semi_dynamic;
pub mod state;
pub mod validity;

pub use distance::DistanceMetric;
pub use error::{Error, Overlap, Result};
pub use math::Pose2;
pub use propagate::{Contact, Propagation, Propagator};
pub use robot::EeAction;
pub use scene::Scene;
pub use state::State;
pub use validity::Invalid;
