//! The C++ API as a C++ application uses it: the example in examples/cpp builds outside
//! the crate against include/ and libpushplan.a with the documented pkg-config command,
//! plans a scene, and catches pushplan::Error for a bad one.

use std::path::PathBuf;
use std::process::Command;

/// target/<profile>/, where cargo put libpushplan.a and build.rs put pushplan.pc.
fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap(); // target/<profile>/deps/cpp_api-<hash>
    exe.parent()
        .and_then(|deps| deps.parent())
        .unwrap()
        .to_path_buf()
}

#[test]
fn the_cpp_example_builds_plans_and_reports_errors() {
    let dir = profile_dir();
    // What a user does first: build the library (cargo copies libpushplan.a into place
    // only for a direct build of the library; it is up to date, so this is quick).
    let mut build = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    build.args(["build", "--lib"]);
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
    let binary = std::env::temp_dir().join(format!("pushplan-plan-scene-{}", std::process::id()));
    let compile = Command::new("g++")
        .args(["-o"])
        .arg(&binary)
        .arg("examples/cpp/plan_scene.cpp")
        .args(flags.split_whitespace())
        .output()
        .expect("g++ runs");
    assert!(
        compile.status.success(),
        "{}",
        String::from_utf8_lossy(&compile.stderr)
    );

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
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("pushplan error:") && stderr.contains("objects[0].mass: must be positive"),
        "{stderr}"
    );
    let _ = std::fs::remove_file(&binary);
}
