//! The `pushplan` command's commands: each does its work, prints its report and says
//! how the process should exit. `src/main.rs` only parses the command line and
//! dispatches here.

mod bench;
mod check;
mod execute;
mod files;
mod pick_place;
mod plan;
mod progress;
mod replan;
mod robot;
mod search_flags;
pub mod within;

pub use bench::{bench, bench_merge, bench_scene, plots};
pub use check::check;
pub use execute::{execute, ExecuteOptions};
pub use files::{draw, export, generate_scenes, generate_shipped_scenes, install};
pub use pick_place::{check_pick_place, pick_place, PickPlaceOptions, PICK_PLACE_FORMAT};
pub use plan::{grasp_goal, plan, PlanOptions};
pub use replan::{replan, ReplanOptions};
pub use robot::{allowed_collisions_of, robot, RobotQuery};
pub use search_flags::SearchFlags;

/// The cores this process may use (at least 1): the default of `plan --threads` and
/// `bench --jobs`.
pub fn cores() -> u32 {
    std::thread::available_parallelism().map_or(1, |n| n.get() as u32)
}

/// Runs a command and says how the process exits: its own code, 2 after bad input (the
/// message printed), 3 after a panic. A panic is a bug in pushplan, never the user's
/// input: it is reported in one line, not as a backtrace.
pub fn exit_code(
    command: impl FnOnce() -> Result<std::process::ExitCode, String>,
) -> std::process::ExitCode {
    std::panic::set_hook(Box::new(|info| {
        // mesh-loader panics on some malformed COLLADA files; the model catches that panic
        // and refuses the file with an error naming it (`robot::mesh`): no bug to report.
        let in_mesh_loader = info
            .location()
            .is_some_and(|l| l.file().contains("mesh-loader"));
        if !in_mesh_loader {
            eprintln!("internal error: {info} (a bug in pushplan: please report it)");
        }
    }));
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(command)) {
        Ok(Ok(code)) => code,
        Ok(Err(message)) => {
            eprintln!("error: {message}");
            std::process::ExitCode::from(2)
        }
        Err(_) => std::process::ExitCode::from(3),
    }
}

#[cfg(test)]
mod tests {
    use super::exit_code;
    use std::process::ExitCode;

    #[test]
    fn a_panic_exits_with_3_and_bad_input_with_2() {
        assert_eq!(exit_code(|| panic!("a bug")), ExitCode::from(3));
        assert_eq!(exit_code(|| Err("bad input".into())), ExitCode::from(2));
        assert_eq!(exit_code(|| Ok(ExitCode::from(1))), ExitCode::from(1));
        assert_eq!(exit_code(|| Ok(ExitCode::SUCCESS)), ExitCode::SUCCESS);
    }
}
