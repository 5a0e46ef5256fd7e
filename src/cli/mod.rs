//! The `pushplan` command's commands: each does its work, prints its report and says
//! how the process should exit. `src/main.rs` only parses the command line and
//! dispatches here.

mod bench;
mod check;
mod execute;
mod files;
mod plan;

pub use bench::{bench, bench_merge, bench_scene, plots, BenchOptions};
pub use check::check;
pub use execute::execute;
pub use files::{draw, generate_scenes, install};
pub use plan::{plan, PlanOptions};
