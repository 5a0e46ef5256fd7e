//! The model's tests, in one binary: they need no OMPL and no C++ compiler
//! (`cargo test -p pushplan-model`). Paths are relative to the repository root: `scenes`
//! and `robots` beside this crate's manifest link to the root's folders.

mod common;

mod collision_matrix;
mod distance;
mod footprint;
mod generate;
mod kinematics;
mod observed_start;
mod physics;
mod pushing;
mod scene_check;
mod scene_errors;
mod scenes;
mod srdf;
mod tipping;
mod urdf;
mod validity;
mod wgr;
