//! `--time` bounds the whole `plan` command, within 5 % + 0.2 s (issue 59). A test binary
//! of its own: cargo runs test binaries one after another, so these wall times are not
//! shared with the other tests' processes on a 2-core machine (under the integration
//! suite's load a 1 s search once took 2.7 s of wall time).

#[path = "../integration/common.rs"]
mod common;

use common::Scratch;
use std::path::Path;

/// `pushplan args` in the crate's folder: exit code, stdout, stderr.
fn pushplan(args: &[&str]) -> (i32, String, String) {
    common::pushplan_in(Path::new("."), args)
}

/// Wall time (s) of `pushplan args` and its exit code and stdout.
fn timed(args: &[&str]) -> (f64, i32, String) {
    let started = std::time::Instant::now();
    let (code, stdout, stderr) = pushplan(args);
    let wall = started.elapsed().as_secs_f64();
    assert!((0..=1).contains(&code), "{args:?}: {stdout}{stderr}");
    (wall, code, stdout)
}

/// `--time` bounds the whole `plan` command, within 5 % + 0.2 s: the search, the
/// robustness checks, shortcutting, re-simulating and writing. The reproducers: a
/// thousand robustness trials ran 8 s past a 2 s limit (a check measured twice, neither
/// stopping at the limit), and a path of tens of thousands of 0.1 ms steps was
/// re-simulated three times after the search had used the whole limit. A run over the
/// bound is tried once more before it fails: the machine may be shared. PDST alone may
/// finish an iteration past the limit, which the model cannot cut (PDST propagates its
/// motions again, one step at a time, to split them and to return its path): on
/// `fine_steps.yaml` (0.1 ms steps) one iteration took 0.1-0.45 s on the 2-core VM, so
/// PDST's bound there is half a second longer.
#[test]
fn the_time_limit_bounds_the_whole_plan_command() {
    let scratch = Scratch::new("time-limit");
    let out = scratch.join("plan.json");
    let out = out.to_str().unwrap();
    let within = |args: &[&str], seconds: f64, iteration: f64| -> (i32, String) {
        let bound = 1.05 * seconds + 0.2 + iteration;
        let mut walls = vec![];
        for _ in 0..2 {
            let (wall, code, stdout) = timed(args);
            if wall <= bound {
                return (code, stdout);
            }
            walls.push(wall);
        }
        panic!("{args:?}: {walls:?} s, past {bound:.2} s");
    };
    let (code, stdout) = within(
        &[
            "plan",
            "scenes/benchmark/scene_05.yaml",
            "--robust",
            "1000",
            "--time",
            "2",
            "--threads",
            "1",
            "--quiet",
            "--out",
            out,
        ],
        2.0,
        0.0,
    );
    assert_eq!(code, 0, "{stdout}");
    // Its robustness record, over the trials the limit left, is what `check` measures.
    let (code, checked, stderr) = pushplan(&["check", out, "--path-only"]);
    assert_eq!(code, 0, "{checked}{stderr}");
    let (code, checked, stderr) = pushplan(&["check", out]);
    let plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap();
    let record = &plan["robustness"];
    // Whether the clock cut the check depends on the machine and the solution found: on the
    // 2-core VM, with a benchmark beside it, it stopped after 548 of the thousand worlds; an
    // idle or faster machine may finish a short solution's check within the 2 s. Cut, the
    // plan cannot be made again, and `check` says where the clock stopped; finished, the
    // record is the whole check, and `check` judges it as any other. The message on a cut
    // record is checked without a clock in tests/integration/cli.rs.
    if let Some(asked) = record["asked"].as_u64() {
        assert_eq!(code, 1, "{checked}{stderr}");
        assert_eq!(asked, 1000, "{record}");
        let trials = record["trials"].as_u64().unwrap();
        assert!(
            checked.contains(&format!(
                "the time limit cut its robustness check short, at {trials} of the 1000 \
                 perturbed worlds asked"
            )) && checked.ends_with("path OK, plan not confirmed\n"),
            "{checked}"
        );
    } else {
        assert_eq!(record["trials"], 1000, "{record}");
        assert!(
            code <= 1 && !checked.contains("differs"),
            "{checked}{stderr}"
        );
    }
    // With --grasp, a reach follows the pushing within the same limit.
    within(
        &[
            "plan",
            "scenes/herb_fig1_clutter.yaml",
            "--grasp",
            "--time",
            "3",
            "--quiet",
            "--out",
            out,
        ],
        3.0,
        0.0,
    );
    for planner in [
        "push_kpiece",
        "pcrrt",
        "static",
        "kpiece",
        "est",
        "pdst",
        "sst",
    ] {
        let (_, stdout) = within(
            &[
                "plan",
                "tests/data/fine_steps.yaml",
                "--planner",
                planner,
                "--time",
                "1",
                "--quiet",
                "--out",
                out,
            ],
            1.0,
            if planner == "pdst" { 0.5 } else { 0.0 },
        );
        let (code, checked, stderr) = pushplan(&["check", out]);
        assert!(
            code <= 1 && !checked.contains("differs"),
            "{planner}: {stdout}{checked}{stderr}"
        );
    }
}
