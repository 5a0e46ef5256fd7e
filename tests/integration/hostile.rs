//! Hostile and clumsy input to the command line, each case from a reproducer that once
//! panicked, crashed, hung or passed a tampered plan: plan files with absurd step
//! counts or the wrong number of values, tampered plans, a plan naming another file as
//! its scene, object names that are markup. Exit codes: 0 done, 1 failed or not solved,
//! 2 bad input, never a panic (101) or a signal.

use crate::common;

use serde_json::Value;
use std::path::{Path, PathBuf};

fn pushplan(args: &[&str]) -> (i32, String, String) {
    common::pushplan_in(Path::new("."), args)
}

/// Plans the single-object scene into `dir/base.json` (solved, 2 s, no shortcutting).
fn base_plan(dir: &Path) -> (PathBuf, Value) {
    let path = dir.join("base.json");
    common::plan_solved("scenes/herb_single_object.yaml", &path, &[]);
    let plan = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    (path, plan)
}

/// A change made to a plan file's JSON.
type Edit = Box<dyn Fn(&mut Value)>;

/// Writes `plan` with `edit` applied as `dir/name`.
fn tampered(dir: &Path, plan: &Value, name: &str, edit: impl Fn(&mut Value)) -> PathBuf {
    let mut plan = plan.clone();
    edit(&mut plan);
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_string(&plan).unwrap()).unwrap();
    path
}

#[test]
fn malformed_plan_files_are_bad_input_for_check_render_and_execute() {
    let scratch = common::Scratch::new("hostile-malformed-plans");
    let (_, plan) = base_plan(scratch.path());
    let cases: [(&str, &str, Edit); 9] = [
        // Steps beyond any plan: a capacity overflow, a 2.4 TB allocation, a minute.
        (
            "huge_steps.json",
            "controls[0].steps",
            Box::new(|p| p["controls"][0]["steps"] = Value::from(u64::MAX / 2 + 1)),
        ),
        (
            "many_steps.json",
            "controls[0].steps",
            Box::new(|p| p["controls"][0]["steps"] = Value::from(10_000_000u64)),
        ),
        // One null-space value too many: render panicked in nalgebra.
        (
            "nullspace.json",
            "controls[0].nullspace",
            Box::new(|p| {
                p["controls"][0]["nullspace"]
                    .as_array_mut()
                    .unwrap()
                    .push(Value::from(0.1))
            }),
        ),
        (
            "short_state.json",
            "controls[0].state",
            Box::new(|p| {
                p["controls"][0]["state"]["q"].as_array_mut().unwrap().pop();
            }),
        ),
        (
            "joints.json",
            "joints",
            Box::new(|p| p["joints"].as_array_mut().unwrap().reverse()),
        ),
        // Settings and metrics the re-simulation cannot give, each checked for what it
        // can be (check said "plan OK").
        (
            "before_negative.json",
            "metrics.before_shortcut",
            Box::new(|p| p["metrics"]["before_shortcut"]["ee_length"] = Value::from(-1e308)),
        ),
        (
            "time_limit.json",
            "time_limit: must be in (0, 86400]",
            Box::new(|p| p["time_limit"] = Value::from(-1.0)),
        ),
        (
            "threads.json",
            "threads: must be in [1, 256]",
            Box::new(|p| p["threads"] = Value::from(0)),
        ),
        // check measures the record's rate again over its trials: a trillion of them
        // would never end.
        (
            "trials.json",
            "robustness.trials: must be in [1, 1000]",
            Box::new(|p| p["robustness"]["trials"] = Value::from(1_000_000_000_000u64)),
        ),
    ];
    assert_eq!(
        plan["shortcut"],
        Value::from(0.0),
        "made without shortcutting"
    );
    for (name, field, edit) in cases {
        let path = tampered(scratch.path(), &plan, name, edit);
        let path = path.to_str().unwrap();
        let out_dir = scratch.join("pictures");
        for args in [
            vec!["check", path],
            vec!["render", path, "--out", out_dir.to_str().unwrap()],
            vec!["execute", path, "--trials", "1"],
        ] {
            let (code, stdout, stderr) = pushplan(&args);
            assert_eq!(code, 2, "{args:?}: {stdout}{stderr}");
            assert!(
                stderr.contains(name) && stderr.contains(field),
                "{args:?}: the message names the file and the field: {stderr}"
            );
        }
    }
}

#[test]
fn check_compares_everything_a_plan_file_claims_with_the_re_simulation() {
    let scratch = common::Scratch::new("hostile-tampered-plans");
    let (path, plan) = base_plan(scratch.path());
    let (code, stdout, _) = pushplan(&["check", path.to_str().unwrap()]);
    assert_eq!(code, 0, "the untouched plan checks: {stdout}");
    let pushed = plan["controls"]
        .as_array()
        .unwrap()
        .iter()
        .position(|c| !c["contacts"].as_array().unwrap().is_empty())
        .expect("the plan pushes the box");
    let cases: [(&str, String, Edit); 9] = [
        // The reproducer: a joint trajectory sample and `solved` changed; "plan OK".
        (
            "trajectory.json",
            "trajectory.q[10][0]".into(),
            Box::new(|p| p["trajectory"]["q"][10] = Value::from(vec![9.0; 7])),
        ),
        (
            "solved.json",
            "solved".into(),
            Box::new(|p| p["solved"] = Value::from(false)),
        ),
        (
            "force.json",
            format!("controls[{pushed}].contacts[0].force"),
            Box::new(move |p| p["controls"][pushed]["contacts"][0]["force"] = Value::from(1.0)),
        ),
        (
            "link.json",
            format!("controls[{pushed}].contacts[0].link"),
            Box::new(move |p| {
                p["controls"][pushed]["contacts"][0]["link"] = Value::from("wam_base")
            }),
        ),
        (
            "duration.json",
            "metrics.after_shortcut.duration".into(),
            Box::new(|p| p["metrics"]["after_shortcut"]["duration"] = Value::from(1.0)),
        ),
        (
            "step.json",
            "step".into(),
            Box::new(|p| p["step"] = Value::from(0.02)),
        ),
        // Without shortcutting the path as found is the plan: its metrics are the
        // re-simulation's too (check said "plan OK").
        (
            "before_huge.json",
            "metrics.before_shortcut.duration".into(),
            Box::new(|p| {
                p["metrics"]["before_shortcut"]["duration"] = Value::from(u64::MAX as f64)
            }),
        ),
        // The robustness record's rate is measured again (the plan's seed, the record's
        // trials): it was taken on trust.
        (
            "robustness.json",
            "robustness.success_rate".into(),
            Box::new(|p| p["robustness"]["success_rate"] = Value::from(0.125)),
        ),
        // The start differs from the scene's: check said so, then "plan OK".
        (
            "start.json",
            "start".into(),
            Box::new(|p| p["start"]["objects"][0][0] = Value::from(0.7)),
        ),
    ];
    // execute plays only the trajectory the controls give (a file of millions of
    // samples would run for hours).
    let longer = tampered(scratch.path(), &plan, "longer.json", |p| {
        for field in ["times", "q", "objects"] {
            let samples = p["trajectory"][field].as_array().unwrap().clone();
            p["trajectory"][field]
                .as_array_mut()
                .unwrap()
                .extend(samples);
        }
    });
    let pictures = scratch.join("pictures");
    for args in [
        vec!["execute", longer.to_str().unwrap(), "--trials", "1"],
        vec![
            "render",
            longer.to_str().unwrap(),
            "--out",
            pictures.to_str().unwrap(),
        ],
    ] {
        let (code, _, stderr) = pushplan(&args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(
            stderr.contains("longer.json: trajectory: not the one"),
            "{args:?}: {stderr}"
        );
    }
    for (name, field, edit) in cases {
        let path = tampered(scratch.path(), &plan, name, edit);
        let (code, stdout, stderr) = pushplan(&["check", path.to_str().unwrap()]);
        assert_eq!(code, 1, "{name}: {stdout}{stderr}");
        assert!(
            stdout.contains(&format!("  {field}: ")) && stdout.ends_with("plan FAILED\n"),
            "{name}: names {field}: {stdout}"
        );
    }
}

#[test]
fn check_makes_the_plan_again_and_names_what_its_settings_do_not_make() {
    // A shortcut plan: its path as found (the metrics before shortcutting) is not in the
    // file, and no re-simulation can say which planner, seed or settings made it. (Seed 1:
    // a seed whose plan shortcutting shortens; seed 3's no longer is, since the arm
    // clearance reads the gap at a step's end too.)
    let scratch = common::Scratch::new("hostile-remade-plans");
    let path = scratch.join("base.json");
    let (code, stdout, stderr) = pushplan(&[
        "plan",
        "scenes/herb_single_object.yaml",
        "--seed",
        "1",
        "--time",
        "30",
        "--shortcut",
        "0.5",
        "--threads",
        "1",
        "--quiet",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let plan: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let (before, after) = (
        &plan["metrics"]["before_shortcut"],
        &plan["metrics"]["after_shortcut"],
    );
    assert_ne!(
        before, after,
        "shortcutting changed the path: {before} {after}"
    );
    let (code, stdout, _) = pushplan(&["check", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{stdout}");
    assert!(
        stdout.contains("the same plan, byte for byte") && stdout.ends_with("plan OK\n"),
        "{stdout}"
    );
    // Each edit passes the re-simulation (it said "plan OK"), and what the file's
    // settings make is another plan: `check` names the first field where they part.
    let cases: [(&str, &str, Edit); 4] = [
        (
            "seed.json",
            "controls",
            Box::new(|p| p["seed"] = Value::from(2)),
        ),
        (
            "planner.json",
            "controls",
            Box::new(|p| {
                p["planner"] = Value::from("pcrrt");
                p["fallback_steps"] = Value::from(0);
            }),
        ),
        (
            "before_huge.json",
            "metrics.before_shortcut.ee_length",
            Box::new(|p| p["metrics"]["before_shortcut"]["ee_length"] = Value::from(1e300)),
        ),
        (
            "before_zero.json",
            "metrics.before_shortcut.joint_length",
            Box::new(|p| p["metrics"]["before_shortcut"]["joint_length"] = Value::from(0.0)),
        ),
    ];
    for (name, field, edit) in cases {
        let edited = tampered(scratch.path(), &plan, name, edit);
        let edited = edited.to_str().unwrap();
        let (code, stdout, stderr) = pushplan(&["check", edited]);
        assert_eq!(code, 1, "{name}: {stdout}{stderr}");
        assert!(
            stdout.contains("states reproduced: yes; goal reached: yes")
                && stdout.contains(&format!("s: {field}"))
                && stdout.contains(": differs from the plan made again")
                && stdout.ends_with("plan FAILED\n"),
            "{name}: names {field}: {stdout}"
        );
        // Re-simulated only, the path passes, and check says what it did not confirm.
        let (code, stdout, _) = pushplan(&["check", edited, "--path-only"]);
        assert_eq!(code, 0, "{name}: {stdout}");
        assert!(
            stdout.contains("as recorded, not made again (--path-only)")
                && stdout.ends_with("path OK\n"),
            "{name}: {stdout}"
        );
    }
    // A setting for another planner is refused as the file is read, naming it.
    let fallback = tampered(scratch.path(), &plan, "fallback.json", |p| {
        p["planner"] = Value::from("kpiece")
    });
    let (code, _, stderr) = pushplan(&["check", fallback.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("fallback.json: fallback_steps 1000000: only push_kpiece falls back"),
        "{stderr}"
    );
}

#[test]
fn a_plan_reads_its_scene_relative_to_itself_and_no_other_file() {
    let scratch = common::Scratch::new("hostile-scene-path");
    let folder = scratch.join("plans");
    std::fs::create_dir(&folder).unwrap();
    let (path, plan) = base_plan(&folder);
    // Stored relative to the plan's folder, so it checks from any folder.
    let scene = plan["scene"].as_str().unwrap();
    assert!(scene.ends_with("scenes/herb_single_object.yaml") && !scene.starts_with('/'));
    let (code, stdout, stderr) =
        common::pushplan_in(scratch.path(), &["check", path.to_str().unwrap()]);
    assert_eq!(code, 0, "checked from another folder: {stdout}{stderr}");
    // A plan naming another file as its scene: refused, and the file is not printed.
    let passwd = tampered(&folder, &plan, "passwd.json", |p| {
        p["scene"] = Value::from("/etc/passwd")
    });
    let (code, stdout, stderr) = pushplan(&["check", passwd.to_str().unwrap()]);
    assert_eq!(code, 2, "{stdout}{stderr}");
    assert!(
        stderr.contains("scene: '/etc/passwd' is not a scene file") && !stderr.contains("root:"),
        "{stderr}"
    );
}

#[test]
fn endless_and_special_files_are_refused_not_read() {
    for command in ["plan", "check", "render"] {
        let (code, stdout, stderr) = pushplan(&[command, "/dev/zero"]);
        assert_eq!(code, 2, "{command}: {stdout}{stderr}");
        assert!(
            stderr.contains("/dev/zero") && stderr.contains("not a regular file"),
            "{command}: {stderr}"
        );
    }
    // A pipe as the scene, or as a plan's scene: opening it would wait for a writer for
    // ever (a test that hangs here fails by CI's time limit).
    let scratch = common::Scratch::new("hostile-fifo");
    let (plan_path, mut plan) = base_plan(scratch.path());
    let fifo = scratch.join("f.yaml");
    let name = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a valid C string and mode.
    assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o644) }, 0);
    plan["scene"] = Value::from("f.yaml");
    let piped = tampered(scratch.path(), &plan, "piped.json", |_| {});
    for args in [
        vec!["plan", fifo.to_str().unwrap()],
        vec!["check", piped.to_str().unwrap()],
    ] {
        let (code, stdout, stderr) = pushplan(&args);
        assert_eq!(code, 2, "{args:?}: {stdout}{stderr}");
        assert!(
            stderr.contains("a pipe (FIFO), not a regular file"),
            "{args:?}: {stderr}"
        );
    }
    assert!(plan_path.is_file());
}

#[test]
fn object_names_cannot_script_the_animation() {
    let scratch = common::Scratch::new("hostile-names");
    let name = "</script><script>document.body.id='pwned'</script>";
    let scene = std::fs::read_to_string("scenes/herb_single_object.yaml")
        .unwrap()
        .replace("green_box", &format!("\"{name}\""))
        .replace(
            "../robots/",
            &format!("{}/robots/", env!("CARGO_MANIFEST_DIR")),
        );
    let scene_path = scratch.join("markup.yaml");
    std::fs::write(&scene_path, scene).unwrap();
    let out = scratch.join("plan.json");
    let pictures = scratch.join("pictures");
    common::plan_solved(
        scene_path.to_str().unwrap(),
        &out,
        &["--render", pictures.to_str().unwrap()],
    );
    let page = std::fs::read_to_string(pictures.join("animation.html")).unwrap();
    assert_eq!(
        page.matches("</script>").count(),
        1,
        "only the page's own script block closes"
    );
    assert!(!page.contains("<script>document"), "{page}");
    for svg in ["snapshots.svg", "timeline.svg"] {
        if let Ok(text) = std::fs::read_to_string(pictures.join(svg)) {
            assert!(!text.contains("<script"), "{svg}");
        }
    }
}

#[test]
fn k_beyond_its_limit_is_refused_on_the_command_line() {
    // --k 100000 --time 2 took 25 s.
    let (code, stdout, stderr) =
        pushplan(&["plan", "scenes/herb_single_object.yaml", "--k", "100000"]);
    assert_eq!(code, 2, "{stdout}{stderr}");
    assert!(stderr.contains("--k: must be in [1, 10000]"), "{stderr}");
}

#[test]
fn counts_are_refused_beyond_the_limits_table_not_allocated() {
    // Each once aborted (an allocation of the count's size), panicked (capacity
    // overflow), wrote files without end or ran far past --time.
    let u32_max = u32::MAX.to_string();
    let u64_max = u64::MAX.to_string();
    let cases: [(&[&str], &str); 9] = [
        (
            &["scenes", "generate", "--count", "4294967296", "--out", "x"],
            "--count: must be in [1, 1000]",
        ),
        (
            &[
                "scenes",
                "generate",
                "--count",
                "9223372036854775808",
                "--out",
                "x",
            ],
            "--count: must be in [1, 1000]",
        ),
        (
            &["scenes", "generate", "--count", "100000", "--out", "x"],
            "--count: must be in [1, 1000]",
        ),
        (
            &["check", "plan.json", "--noise", &u32_max],
            "--noise: must be in [0, 10000]",
        ),
        (
            &["check", "plan.json", "--noise", &u64_max],
            "--noise: must be in [0, 10000]",
        ),
        (
            &["execute", "plan.json", "--trials", &u32_max],
            "--trials: must be in [1, 1000]",
        ),
        (
            &["execute", "plan.json", "--trials", &u64_max],
            "--trials: must be in [1, 1000]",
        ),
        (
            &["pick-place", "--object", "box", "--grasps", &u32_max],
            "--grasps: must be in [1, 1000]",
        ),
        (
            &[
                "plan",
                "scenes/herb_single_object.yaml",
                "--robust",
                "100000",
            ],
            "--robust: must be in [0, 1000]",
        ),
    ];
    for (args, expected) in cases {
        let (code, stdout, stderr) = pushplan(args);
        assert_eq!(code, 2, "{args:?}: {stdout}{stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
    // Reals too: a duration of 10^300 s, a NaN rate.
    for (args, expected) in [
        (
            &["plan", "scenes/herb_single_object.yaml", "--time", "1e300"][..],
            "--time: must be in (0, 86400]",
        ),
        (
            &[
                "plan",
                "scenes/herb_single_object.yaml",
                "--robust-rate",
                "NaN",
            ],
            "--robust-rate: must be in [0, 1]",
        ),
        (
            &["execute", "plan.json", "--speed", "0"],
            "--speed: must be in (0, 100]",
        ),
    ] {
        let (code, stdout, stderr) = pushplan(args);
        assert_eq!(code, 2, "{args:?}: {stdout}{stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
}

#[test]
fn the_documented_limits_are_the_limits_table() {
    let docs = std::fs::read_to_string("docs/commands.md").unwrap();
    for limit in pushplan::limits::ALL {
        let api = match limit.field {
            "" => String::new(),
            field => format!(" / `Options::{field}`"),
        };
        let row = format!(
            "| `{}`{api} | {} | {} |",
            limit.option,
            limit.range(),
            limit.what
        );
        assert!(docs.contains(&row), "docs/commands.md lacks the row {row}");
    }
}

/// A time limit too short for a search to grow its tree (a millisecond, the scene's
/// loading included) gives an unsolved plan of the start alone: once an internal error,
/// "re-simulating the plan does not reproduce it" (no path was compared with the start).
#[test]
fn a_search_with_no_time_writes_the_start_alone() {
    let scratch = common::Scratch::new("hostile-no-time");
    let out = scratch.join("plan.json");
    let out = out.to_str().unwrap();
    let (code, stdout, stderr) = pushplan(&[
        "plan",
        "scenes/herb_single_object.yaml",
        "--time",
        "0.001",
        "--quiet",
        "--out",
        out,
    ]);
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(stdout.contains("not solved"), "{stdout}");
    let (code, checked, _) = pushplan(&["check", out]);
    assert_eq!(code, 1, "{checked}");
    assert!(
        checked.contains("the goal is not reached") && !checked.contains("differs"),
        "{checked}"
    );
}
