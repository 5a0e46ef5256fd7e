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

/// The cores this process may use (at least 1): the default of `plan --threads` and
/// `bench --jobs`.
pub fn cores() -> u32 {
    std::thread::available_parallelism().map_or(1, |n| n.get() as u32)
}
