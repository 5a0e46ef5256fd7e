//! Seeded mutation fuzzing of everything pushplan reads: scene YAML, URDF, meshes and plan
//! files (750, 300, 600 and 300 cases), the command line (24) and the options every front
//! door shares (3000).
//! Each case mutates a shipped file (characters changed, spans deleted or repeated,
//! numbers replaced by extreme values, the text cut short) and feeds it in. Nothing may
//! panic; every error names the file. A smaller sample goes through the command line,
//! where only the exit codes 0 (done), 1 (failed or not solved) and 2 (bad input) may
//! come back. The same seeds give the same cases, so a failure reproduces.

use crate::common;

use pushplan::bridge::OmplSearch;
use pushplan::planner::remake::{remake, Remade};
use pushplan::planning::plan_file::{first_difference, PlanFile};
use pushplan::random::SplitMix64;
use pushplan::robot::urdf::load_urdf;
use pushplan::{EeAction, Propagator, Scene};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::process::Command;

/// Values a number may be replaced by.
const EXTREMES: [&str; 16] = [
    ".nan",
    "NaN",
    ".inf",
    "-.inf",
    "-1",
    "0",
    "-0.0",
    "1e308",
    "-1e308",
    "1e-320",
    "99999999999999999999",
    "null",
    "''",
    "[]",
    "{}",
    "1e6",
];

/// `text` with one to three random mutations.
fn mutate(text: &str, rng: &mut SplitMix64) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for _ in 0..1 + rng.below(3) {
        let n = bytes.len().max(1);
        let at = rng.below(n).min(bytes.len());
        match rng.below(6) {
            // A character changed to one that matters to the formats.
            0 => {
                const SYNTAX: &[u8] = b"[]{}:,-'\"#&*!|>\n 0.e9x<";
                let c = SYNTAX[rng.below(SYNTAX.len())];
                if at < bytes.len() {
                    bytes[at] = c;
                }
            }
            1 => {
                let end = (at + 1 + rng.below(40)).min(bytes.len());
                bytes.drain(at..end);
            }
            2 => {
                let end = (at + 1 + rng.below(80)).min(bytes.len());
                let span = bytes[at..end].to_vec();
                bytes.splice(at..at, span);
            }
            3 => bytes.truncate(at),
            // A number replaced by an extreme value.
            _ => {
                let digits: Vec<usize> = (0..bytes.len())
                    .filter(|&i| bytes[i].is_ascii_digit())
                    .collect();
                if digits.is_empty() {
                    continue;
                }
                let mut start = digits[rng.below(digits.len())];
                while start > 0
                    && (bytes[start - 1].is_ascii_digit() || b".-e".contains(&bytes[start - 1]))
                {
                    start -= 1;
                }
                let mut end = start;
                while end < bytes.len()
                    && (bytes[end].is_ascii_digit() || b".-e".contains(&bytes[end]))
                {
                    end += 1;
                }
                let value = EXTREMES[rng.below(EXTREMES.len())].as_bytes().to_vec();
                bytes.splice(start..end, value);
            }
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

/// Changes one leaf of a JSON document: a number to an extreme one, a string emptied,
/// an array's last element removed or repeated.
fn mutate_value(value: &mut serde_json::Value, rng: &mut SplitMix64) {
    use serde_json::Value;
    const NUMBERS: [f64; 8] = [-1.0, 0.0, 1e308, -1e308, 1e-320, 123_456_789.0, 0.5, 3.0];
    match value {
        Value::Object(map) if !map.is_empty() => {
            let key = map.keys().nth(rng.below(map.len())).unwrap().clone();
            mutate_value(map.get_mut(&key).unwrap(), rng);
        }
        Value::Array(items) if !items.is_empty() && rng.below(4) > 0 => {
            let i = rng.below(items.len());
            mutate_value(&mut items[i], rng);
        }
        Value::Array(items) => {
            if let Some(last) = items.pop() {
                if rng.below(2) == 0 {
                    items.push(last.clone());
                    items.push(last);
                }
            }
        }
        Value::String(text) => text.clear(),
        Value::Bool(b) => *b = !*b,
        _ => *value = Value::from(NUMBERS[rng.below(NUMBERS.len())]),
    }
}

/// Runs `f`; fails the test with `what` if it panics.
fn no_panic<T>(what: &str, f: impl FnOnce() -> T) -> T {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(value) => value,
        Err(_) => panic!("panicked on {what}"),
    }
}

#[test]
fn mutated_scenes_load_or_fail_naming_the_file_and_never_panic() {
    let source = Path::new("scenes/fuzzed.yaml");
    let bases = [
        "scenes/herb_fig1_clutter.yaml",
        "scenes/planar_hand_single_object.yaml",
        "scenes/dense/scene_00.yaml",
    ];
    let mut loaded = 0;
    for (b, base) in bases.iter().enumerate() {
        let text = std::fs::read_to_string(base).unwrap();
        let mut rng = SplitMix64::new(1000 + b as u64);
        for case in 0..250 {
            let mutated = mutate(&text, &mut rng);
            let what = format!("{base}, case {case}:\n{mutated}");
            match no_panic(&what, || Scene::from_yaml(&mutated, source)) {
                Err(e) => assert!(
                    e.to_string().starts_with("scenes/fuzzed.yaml: ")
                        || e.to_string().contains(".urdf"),
                    "{what}\nthe error names the file: {e}"
                ),
                Ok(scene) => {
                    loaded += 1;
                    // What loads also pushes: a short propagation from the start.
                    no_panic(&what, || {
                        Propagator::new(scene.clone()).propagate(
                            &scene.start,
                            &EeAction::planar(0.1, 0.05, 0.2),
                            0.5,
                        )
                    });
                }
            }
        }
    }
    // Some mutations leave a valid scene (a changed comment, a nudged number).
    assert!(loaded > 10, "only {loaded} mutated scenes loaded");
}

#[test]
fn mutated_urdfs_load_or_fail_naming_the_file_and_never_panic() {
    let scratch = common::Scratch::new("fuzz-urdf");
    let text = std::fs::read_to_string("robots/wam7.urdf").unwrap();
    let path = scratch.join("fuzzed.urdf");
    let mut rng = SplitMix64::new(2000);
    for case in 0..300 {
        let mutated = mutate(&text, &mut rng);
        std::fs::write(&path, &mutated).unwrap();
        let what = format!("case {case}:\n{mutated}");
        match no_panic(&what, || {
            load_urdf(&path, "hand", nalgebra::Isometry3::identity())
        }) {
            Err(e) => assert!(
                e.to_string().contains("fuzzed.urdf"),
                "{what}\nthe error names the file: {e}"
            ),
            Ok(chain) => {
                let mut poses = Vec::new();
                no_panic(&what, || {
                    chain.forward_kinematics(&nalgebra::DVector::zeros(chain.dof()), &mut poses)
                });
            }
        }
    }
}

#[test]
fn mutated_plan_files_are_read_and_checked_without_panics() {
    let scratch = common::Scratch::new("fuzz-plans");
    let base = scratch.join("base.json");
    const SCENE: &str = "scenes/herb_single_object.yaml";
    common::plan_solved(SCENE, &base, &[]);
    let text = std::fs::read_to_string(&base).unwrap();
    let path = scratch.join("fuzzed.json");
    let mut rng = SplitMix64::new(3000);
    let mut read = 0;
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let base_plan = PlanFile::read(&base).unwrap();
    let (mut passed, mut remade_otherwise) = (0, 0);
    for case in 0..300 {
        // Half the cases break the JSON; half change a value and stay JSON.
        let mutated = if case % 2 == 0 {
            mutate(&text, &mut rng)
        } else {
            let mut v = value.clone();
            mutate_value(&mut v, &mut rng);
            serde_json::to_string(&v).unwrap()
        };
        std::fs::write(&path, &mutated).unwrap();
        let what = format!("case {case}");
        match no_panic(&what, || PlanFile::read(&path)) {
            Err(e) => assert!(e.contains("fuzzed.json"), "{what}: {e}"),
            Ok(plan) => {
                read += 1;
                match no_panic(&what, || plan.check(&path)) {
                    Err(e) => assert!(
                        e.contains("fuzzed.json") || e.contains(".yaml"),
                        "{what}: {e}"
                    ),
                    // No false "plan OK": a plan whose path passes is made again from its
                    // settings; when that gives the file, it holds what the plan made
                    // says, and its settings, where changed, make it through the command
                    // line's `plan` too.
                    Ok(report) if report.problems.is_empty() => {
                        match no_panic(&what, || remake(&OmplSearch, &plan, &path)) {
                            Err(e) => panic!("{what}: a plan that re-simulates is made again: {e}"),
                            Ok(Remade::Same) => {}
                            Ok(_) => {
                                remade_otherwise += 1;
                                continue;
                            }
                        }
                        let settings = serde_json::to_value(&base_plan.settings).unwrap();
                        let claims = |text: &str| {
                            let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
                            for key in settings.as_object().unwrap().keys() {
                                v.as_object_mut().unwrap().remove(key);
                            }
                            v.as_object_mut().unwrap().remove("robustness");
                            v
                        };
                        let (made, read) = (claims(&base_plan.to_json()), claims(&plan.to_json()));
                        let changed: Vec<String> = read
                            .as_object()
                            .unwrap()
                            .iter()
                            .filter(|(key, value)| made.get(key.as_str()) != Some(value))
                            .map(|(key, value)| {
                                let mut shown = format!("{key}: {value}");
                                shown.truncate(300);
                                shown
                            })
                            .collect();
                        assert!(
                            changed.is_empty(),
                            "{what}: checked OK but not the plan made: {changed:?}"
                        );
                        if plan != base_plan {
                            let mut cli = planned_as(&plan, SCENE, &scratch.join("cli.json"));
                            cli.settings.time_limit = plan.settings.time_limit;
                            assert_eq!(
                                first_difference(&plan, &cli),
                                None,
                                "{what}: checked OK, and `plan` with its settings makes it"
                            );
                        }
                        passed += 1;
                    }
                    Ok(_) => {}
                }
            }
        }
    }
    assert!(read > 10, "only {read} mutated plans were read");
    assert!(
        passed > 0 && remade_otherwise > 0,
        "{passed} mutated plans passed their check, {remade_otherwise} re-simulated but were made otherwise \
         (changes of settings give both)"
    );
}

/// The plan file `pushplan plan` writes to `out` from `scene` with the settings `plan`
/// records (its robustness record's too), with at least 30 s: a plan that is made again
/// within its time limit is the same with more.
fn planned_as(plan: &PlanFile, scene: &str, out: &Path) -> PlanFile {
    let s = &plan.settings;
    let mut args: Vec<String> = vec![
        "plan".into(),
        scene.into(),
        "--quiet".into(),
        "--out".into(),
        out.to_string_lossy().into_owned(),
    ];
    let mut flag = |name: &str, value: String| args.extend([format!("--{name}"), value]);
    flag("planner", s.planner.name().into());
    flag("seed", s.seed.to_string());
    flag("k", s.k.to_string());
    flag("goal-bias", s.goal_bias.to_string());
    flag("time", s.time_limit.max(30.0).to_string());
    flag("shortcut", s.shortcut.to_string());
    flag("threads", s.threads.to_string());
    flag("restart", s.restart_steps.to_string());
    flag("fallback", s.fallback_steps.to_string());
    match &plan.robustness {
        Some(r) => {
            flag("robust", r.trials.to_string());
            flag("robust-rate", r.required_rate.to_string());
            flag("particles", r.particles.to_string());
            flag("robust-shortcut", r.shortcut.to_string());
        }
        None => flag("robust", "0".into()),
    }
    if s.intermediate_states {
        args.push("--intermediate-states".into());
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, stdout, stderr) = common::pushplan_in(Path::new("."), &args);
    assert!(code <= 1, "{args:?}: {stdout}{stderr}");
    PlanFile::read(out).unwrap()
}

/// A binary STL of a box with half extents 5 cm: 12 triangles.
fn box_stl() -> Vec<u8> {
    let (corners, faces) = crate::meshes::box_mesh([0.05; 3]);
    let mut bytes = vec![0u8; 80];
    bytes.extend((faces.len() as u32).to_le_bytes());
    for face in faces {
        bytes.extend([0u8; 12]);
        for v in face {
            for c in corners[v] {
                bytes.extend((c as f32).to_le_bytes());
            }
        }
        bytes.extend([0u8; 2]);
    }
    bytes
}

/// `bytes` with one to three random byte mutations: a byte changed, a span deleted or
/// repeated, four bytes set to an extreme `f32` or count, the file cut short.
fn mutate_bytes(bytes: &[u8], rng: &mut SplitMix64) -> Vec<u8> {
    let mut bytes = bytes.to_vec();
    for _ in 0..1 + rng.below(3) {
        let at = rng.below(bytes.len().max(1)).min(bytes.len());
        match rng.below(5) {
            0 if at < bytes.len() => bytes[at] = rng.below(256) as u8,
            1 => {
                let end = (at + 1 + rng.below(60)).min(bytes.len());
                bytes.drain(at..end);
            }
            2 => {
                let end = (at + 1 + rng.below(100)).min(bytes.len());
                let span = bytes[at..end].to_vec();
                bytes.splice(at..at, span);
            }
            3 if at + 4 <= bytes.len() => {
                let extreme: [u8; 4] = match rng.below(5) {
                    0 => f32::NAN.to_le_bytes(),
                    1 => f32::INFINITY.to_le_bytes(),
                    2 => f32::MAX.to_le_bytes(),
                    3 => u32::MAX.to_le_bytes(),
                    _ => 0u32.to_le_bytes(),
                };
                bytes[at..at + 4].copy_from_slice(&extreme);
            }
            _ => bytes.truncate(at),
        }
    }
    bytes
}

/// Meshes as a URDF or a scene names them: OBJ and COLLADA text (the shipped robot's)
/// and binary STL, mutated. Each loads as a convex hull or fails naming the file.
#[test]
fn mutated_meshes_load_or_fail_naming_the_file_and_never_panic() {
    use pushplan::robot::mesh::load_convex_mesh;
    let scratch = common::Scratch::new("fuzz-meshes");
    let mut loaded = 0;
    for (b, (extension, base)) in [
        ("obj", std::fs::read("robots/meshes/wam7/hand.obj").unwrap()),
        (
            "dae",
            std::fs::read("robots/meshes/wam7/wam_link4.dae").unwrap(),
        ),
        ("stl", box_stl()),
    ]
    .into_iter()
    .enumerate()
    {
        let path = scratch.join(&format!("fuzzed.{extension}"));
        let mut rng = SplitMix64::new(5000 + b as u64);
        for case in 0..200 {
            let mutated = match extension {
                "stl" => mutate_bytes(&base, &mut rng),
                _ => mutate(std::str::from_utf8(&base).unwrap(), &mut rng).into_bytes(),
            };
            std::fs::write(&path, &mutated).unwrap();
            let what = format!("{extension}, case {case}");
            match no_panic(&what, || load_convex_mesh(&path, [1.0; 3])) {
                Err(e) => assert!(
                    e.to_string().contains(&format!("fuzzed.{extension}")),
                    "{what}: the error names the file: {e}"
                ),
                Ok(_) => loaded += 1,
            }
        }
    }
    assert!(loaded > 30, "only {loaded} mutated meshes loaded");
}

#[test]
fn the_command_line_answers_mutated_input_with_exit_codes_0_1_or_2() {
    let scratch = common::Scratch::new("fuzz-cli");
    let text = std::fs::read_to_string("scenes/herb_single_object.yaml")
        .unwrap()
        .replace(
            "../robots/",
            &format!("{}/robots/", env!("CARGO_MANIFEST_DIR")),
        );
    let scene = scratch.join("fuzzed.yaml");
    let plan = scratch.join("plan.json");
    let mut rng = SplitMix64::new(4000);
    for case in 0..24 {
        let mutated = mutate(&text, &mut rng);
        std::fs::write(&scene, &mutated).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_pushplan"))
            .args([
                "plan",
                scene.to_str().unwrap(),
                "--time",
                "0.3",
                "--shortcut",
                "0",
            ])
            .args(["--threads", "1", "--quiet", "--out", plan.to_str().unwrap()])
            .output()
            .unwrap();
        let code = out.status.code();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            matches!(code, Some(0..=2)),
            "case {case}: exit {code:?}: {stderr}\n{mutated}"
        );
        if code == Some(2) {
            assert!(stderr.contains("fuzzed.yaml"), "case {case}: {stderr}");
        }
    }
}

/// Seeded fuzzing of the options every front door shares (`RunSettings`, the C++ API's
/// `Options` resolve to it): each case sets every count, duration and rate to a value near
/// or far outside its limit. `check` must never panic, and must refuse a case exactly when
/// a value lies outside the range docs/commands.md states, compared here field by field.
#[test]
fn fuzzed_options_are_refused_exactly_outside_their_limits() {
    use pushplan::limits::Front;
    let mut rng = SplitMix64::new(59);
    let counts: [u64; 9] = [
        0,
        1,
        2,
        64,
        65,
        256,
        257,
        1_000_000_000,
        u64::from(u32::MAX),
    ];
    let reals: [f64; 11] = [
        f64::NAN,
        f64::INFINITY,
        -1.0,
        0.0,
        1e-9,
        0.5,
        1.0,
        1.5,
        86_400.0,
        86_401.0,
        1e308,
    ];
    for case in 0..3_000 {
        let mut run = common::run_settings("push_kpiece");
        let count = |rng: &mut SplitMix64| counts[(rng.next_u64() % 9) as usize] as u32;
        let real = |rng: &mut SplitMix64| reals[(rng.next_u64() % 11) as usize];
        run.k = count(&mut rng);
        run.threads = count(&mut rng);
        run.robust_trials = count(&mut rng);
        run.robust_particles = count(&mut rng) % 128;
        run.time_limit = real(&mut rng);
        run.shortcut = real(&mut rng);
        run.robust_shortcut = real(&mut rng);
        run.goal_bias = real(&mut rng);
        run.robust_rate = real(&mut rng);
        let within = |v: f64, low: f64, high: f64| v.is_finite() && low <= v && v <= high;
        let allowed = (1..=10_000).contains(&run.k)
            && (1..=256).contains(&run.threads)
            && run.robust_trials <= 1_000
            && run.robust_particles <= 64
            && within(run.time_limit, f64::MIN_POSITIVE, 86_400.0)
            && within(run.shortcut, 0.0, 86_400.0)
            && within(run.robust_shortcut, 0.0, 86_400.0)
            && within(run.goal_bias, 0.0, 1.0)
            && within(run.robust_rate, 0.0, 1.0)
            && (run.robust_particles == 0 || run.robust_trials > 0);
        let checked = no_panic(&format!("options case {case}"), || {
            run.check(Front::CppOptions)
        });
        assert_eq!(
            checked.is_ok(),
            allowed,
            "case {case}: {run:?}: {checked:?}"
        );
        if let Err(message) = checked {
            assert!(message.starts_with("Options::"), "case {case}: {message}");
        }
    }
}
