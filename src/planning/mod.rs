//! Planning on the model: what a planner searches for and what is done with what it finds.
//!
//! - the problem ([`Problem`]: the scene, and Static RRT's pinned clutter) and the planner
//!   kinds ([`PlannerKind`]);
//! - paths of controls ([`path`]), their re-simulation, shortcutting ([`shortcut`]),
//!   robustness to parameter noise ([`robustness`]), executable trajectories
//!   ([`trajectory`]), the one way a found path is finished ([`finish`]) and mending the
//!   rest of a plan a world off the model broke ([`mend`]);
//! - plan files ([`plan_file`]);
//! - DARRT's primitives ([`darrt`]), straight joint-space lines ([`transit`]), reaching a
//!   grasp ([`reach`]) and the manipulation graph ([`manipulation`]);
//! - Static RRT's clutter as obstacles ([`static_clutter`]) and execution in an independent
//!   3D engine ([`execute`]); the trajectory in formats other programs read ([`export`]).
//!
//! Nothing here knows OMPL or the bridge: the searches themselves are C++ (`cpp/`).

pub mod darrt;
mod deadline;
pub mod execute;
pub mod export;
mod finish;
mod kind;
pub mod manipulation;
pub mod mend;
pub mod observed;
pub mod path;
pub mod plan_file;
mod problem;
pub mod reach;
pub mod rest;
pub mod robustness;
mod run_settings;
pub mod shortcut;
pub mod static_clutter;
pub mod trajectory;
pub mod transit;

pub use deadline::{deadline, passed, time_left, CommandDeadline};
pub use finish::{
    finish, unseen_seed, FinishSettings, FinishedPath, MeasuredRate, RobustRequirement,
    ShortcutReport,
};
pub use kind::PlannerKind;
pub use problem::Problem;
pub use run_settings::{
    RunSettings, DEFAULT_ROBUST_RATE, DEFAULT_ROBUST_SHORTCUT, PLAN_ROBUST_TRIALS,
};
