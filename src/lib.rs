//! pushplan: whole-arm rearrangement planning by quasistatic pushing.
//!
//! The Rust model behind the planner of King, Haustein, Srinivasa and Asfour,
//! "Nonprehensile Whole Arm Rearrangement Planning on Physics Manifolds":
//!
//! - [`scene`]: scene files (YAML) and their validated form;
//! - [`robot`]: robots from URDF (and the planar hand), kinematics, the constraint
//!   projection of actions onto the pushing plane;
//! - [`collision`]: shapes and geometric queries; [`contact`]: arm-object contacts;
//! - [`physics`]: quasistatic planar pushing (limit surface, friction, complementarity);
//! - [`validity`], [`distance`], and [`propagate`] (`ConstrainedProp`, Alg. 2).
//!
//! Units are SI throughout (m, rad, s, kg, N); the world frame has z up.

pub mod benchmark;
pub mod cli;
pub mod collision;
pub mod contact;
pub mod darrt;
pub mod distance;
pub mod error;
pub mod execute;
pub mod ffi;
pub mod input;
pub mod install;
pub mod manipulation;
pub mod math;
pub mod path;
pub mod physics;
pub mod plan;
pub mod planner;
pub mod propagate;
pub mod random;
pub mod reach;
pub mod render;
pub mod robot;
pub mod robustness;
pub mod scene;
pub mod semi_dynamic;
pub mod shortcut;
pub mod state;
pub mod static_clutter;
pub mod trajectory;
pub mod validity;

pub use distance::DistanceMetric;
pub use error::{Error, Result};
pub use math::Pose2;
pub use propagate::{Contact, Propagation, Propagator};
pub use robot::EeAction;
pub use scene::Scene;
pub use state::State;
pub use validity::Invalid;
