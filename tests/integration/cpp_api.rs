//! The C++ API as a C++ application uses it: the example in examples/cpp builds outside
//! the crate against include/ and libpushplan.a with the documented pkg-config command,
//! plans a scene, and catches pushplan::Error for a bad one.

use std::path::{Path, PathBuf};
use std::process::Command;

/// target/<profile>/, where cargo put libpushplan.a and build.rs put pushplan.pc.
fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap(); // target/<profile>/deps/cpp_api-<hash>
    exe.parent()
        .and_then(|deps| deps.parent())
        .unwrap()
        .to_path_buf()
}

/// Builds `source` the way a user does (after `cargo build --lib`, with the documented
/// pkg-config command) into a binary in the temporary folder.
fn compile(source: &str, name: &str) -> PathBuf {
    compile_with(source, name, &[])
}

/// [`compile`] with extra compiler arguments.
fn compile_with(source: &str, name: &str, extra: &[String]) -> PathBuf {
    let dir = profile_dir();
    // What a user does first: build the library (cargo copies libpushplan.a into place
    // only for a direct build of the library). With --tests it is the test build's own
    // library, up to date: nothing is built again.
    let mut build = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    build.args(["build", "--lib", "--tests"]);
    if dir.ends_with("release") {
        build.arg("--release");
    }
    let built = build.output().expect("cargo runs");
    assert!(
        built.status.success(),
        "{}",
        String::from_utf8_lossy(&built.stderr)
    );
    let pc = dir.join("pushplan.pc");
    assert!(
        pc.is_file() && dir.join("libpushplan.a").is_file(),
        "no library in {}",
        dir.display()
    );
    let flags = Command::new("pkg-config")
        .args(["--cflags", "--libs"])
        .arg(&pc)
        .output()
        .expect("pkg-config runs");
    assert!(
        flags.status.success(),
        "{}",
        String::from_utf8_lossy(&flags.stderr)
    );
    let flags = String::from_utf8(flags.stdout).unwrap();
    let binary = std::env::temp_dir().join(format!("pushplan-{name}-{}", std::process::id()));
    let compile = Command::new("g++")
        .args(["-o"])
        .arg(&binary)
        .arg(source)
        .args(extra)
        .args(flags.split_whitespace())
        .output()
        .expect("g++ runs");
    assert!(
        compile.status.success(),
        "{}",
        String::from_utf8_lossy(&compile.stderr)
    );
    binary
}

#[test]
fn the_cpp_example_builds_plans_and_reports_errors() {
    let binary = compile("examples/cpp/plan_scene.cpp", "plan-scene");
    let run = Command::new(&binary)
        .args(["scenes/herb_single_object.yaml", "1"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(
        stdout.starts_with("herb-single-object: solved in"),
        "{stdout}"
    );
    assert!(stdout.contains("green_box ends at"), "{stdout}");
    // Shortcutting through the C++ API (on by default): the path never gets longer.
    let line = stdout
        .lines()
        .find(|l| l.contains("manipulator path"))
        .expect("metrics printed");
    let numbers: Vec<f64> = line
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .filter_map(|w| w.parse().ok())
        .collect();
    assert!(
        numbers.len() >= 2 && numbers[0] <= numbers[1] + 1e-9,
        "after vs found: {line}"
    );
    // The executable trajectory through the C++ API is the plan file's.
    let plan_file = std::env::temp_dir().join(format!("pushplan-cpp-{}.json", std::process::id()));
    let cli = Command::new(env!("CARGO_BIN_EXE_pushplan"))
        .args([
            "plan",
            "scenes/herb_single_object.yaml",
            "--seed",
            "1",
            "--time",
            "30",
            "--quiet",
        ])
        .arg("--out")
        .arg(&plan_file)
        .output()
        .unwrap();
    assert_eq!(cli.status.code(), Some(0));
    let plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&plan_file).unwrap()).unwrap();
    let _ = std::fs::remove_file(&plan_file);
    let times = plan["trajectory"]["times"].as_array().unwrap();
    let last_q0 = plan["trajectory"]["q"].as_array().unwrap().last().unwrap()[0]
        .as_f64()
        .unwrap();
    let line = stdout
        .lines()
        .find(|l| l.contains("trajectory:"))
        .expect("trajectory printed");
    let numbers: Vec<f64> = line
        .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter_map(|w| w.parse().ok())
        .collect();
    assert_eq!(numbers[0] as usize, times.len(), "{line}");
    assert_eq!(numbers[1], 50.0, "{line}");
    assert!(
        (numbers[2] - times.last().unwrap().as_f64().unwrap()).abs() < 1e-4,
        "{line}"
    );
    assert!((numbers[3] - last_q0).abs() < 1e-4, "{line} vs {last_q0}");

    // Push, then grasp: Planner::reach from where the plan ends.
    let run = Command::new(&binary)
        .args(["scenes/herb_fig1_clutter.yaml", "5", "green_box"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert_eq!(run.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("then a grasp of green_box: reached through"),
        "{stdout}"
    );

    // A scene given as text (Planner::fromYaml): relative paths resolve against the
    // working directory of the named source.
    let text = std::fs::read_to_string("scenes/planar_hand_single_object.yaml").unwrap();
    let mut child = Command::new(&binary)
        .arg("-")
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(text.as_bytes())
        .unwrap();
    let run = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert_eq!(run.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.starts_with("planar-hand-single-object: solved"),
        "{stdout}"
    );

    // A bad scene: the C++ exception carries the file and the field.
    let bad = std::env::temp_dir().join(format!("pushplan-bad-{}.yaml", std::process::id()));
    let text = std::fs::read_to_string("scenes/herb_single_object.yaml")
        .unwrap()
        .replace("mass: 1.0", "mass: -1.0");
    std::fs::write(
        &bad,
        text.replace(
            "../robots",
            &format!("{}/robots", env!("CARGO_MANIFEST_DIR")),
        ),
    )
    .unwrap();
    let run = Command::new(&binary).arg(&bad).output().unwrap();
    let _ = std::fs::remove_file(&bad);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("pushplan error:") && stderr.contains("objects[0].mass: must be positive"),
        "{stderr}"
    );
    let _ = std::fs::remove_file(&binary);
}

#[test]
fn the_cpp_api_keeps_its_contract() {
    // Planner kinds and names, OMPL's log level left as found, every failure as
    // pushplan::Error: tests/cpp/api_contract.cpp checks each and prints what it checked.
    let binary = compile("tests/cpp/api_contract.cpp", "api-contract");
    run_checks(&binary, 82);
}

/// Runs a C++ test program (tests/cpp/expect.h) and checks that it passed exactly
/// `checks` checks and failed none.
fn run_checks(binary: &Path, checks: usize) {
    let run = Command::new(binary).output().unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    let _ = std::fs::remove_file(binary);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert_eq!(
        stdout.lines().filter(|l| l.starts_with("ok: ")).count(),
        checks,
        "{stdout}"
    );
}

/// Builds a C++ test program of the library's internals and runs its checks (run_checks).
fn run_internal_checks(source: &str, name: &str, checks: usize) {
    run_checks(&compile_with(source, name, &internal_includes()), checks);
}

/// The library's internal headers: cxx's generated ones, the crate's, and the C++ twins
/// of the bridge's Rust types, which the build script put under OUT_DIR.
fn internal_includes() -> [String; 3] {
    let out = PathBuf::from(env!("OUT_DIR"));
    ["cxxbridge/include", "cxxbridge/crate", "twins"]
        .map(|d| format!("-I{}", out.join(d).display()))
}

#[test]
fn every_failure_leaves_the_cpp_api_as_pushplan_error() {
    run_internal_checks("tests/cpp/error_conversion.cpp", "error-conversion", 4);
}

#[test]
fn a_time_limited_search_lifts_its_limit_when_it_returns() {
    run_internal_checks(
        "tests/cpp/time_limited_search.cpp",
        "time-limited-search",
        3,
    );
}

#[test]
fn parallel_kpiece_with_one_lane_is_ompl_kpiece1_bit_for_bit() {
    run_internal_checks("tests/cpp/parallel_kpiece.cpp", "parallel-kpiece", 8);
}

#[test]
fn push_kpiece_falls_back_to_pc_rrt_only_without_progress_and_takes_over_where_pc_rrt_moves_the_goal(
) {
    run_internal_checks("tests/cpp/fallback.cpp", "fallback", 15);
}

#[test]
fn restarts_announce_each_attempt_and_push_kpiece_refines_its_grid_after_the_first() {
    run_internal_checks("tests/cpp/restarts.cpp", "restarts", 5);
}

#[test]
fn helper_threads_start_on_another_core_then_use_any() {
    run_internal_checks("tests/cpp/helper_thread.cpp", "helper-thread", 4);
}
