//! pushplan's integration tests, in one binary (one link against OMPL): the planner, its
//! command line, the C++ API and the OMPL layer, benchmarking, execution and the oracles.
//! The model's own tests are the model crate's (`model/tests/model`).

mod common;

mod bench;
mod chain;
mod cli;
mod cpp_api;
mod darrt;
mod execute;
mod export;
mod fcl_oracle;
mod fuzz;
mod hostile;
mod install;
mod layers;
mod manipulation;
mod meshes;
mod nearest;
mod particles;
mod planner;
mod python;
mod reach;
mod render;
mod replan;
mod robustness;
mod semi_dynamic;
mod shortcut;
mod slurm;
mod writes;
