//! `pushplan install` as a C++ user meets it: install into a prefix, move the prefix
//! (nothing may point back into the build), then build the C++ examples against it with
//! CMake (`find_package(pushplan)` beside `find_package(ompl)`; the C++ API and the
//! public OMPL layer with OMPL's SST, KPIECE1 and Benchmark) and with pkg-config, and
//! run them.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn ok(what: &str, output: std::io::Result<Output>) -> Output {
    let output = output.unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(
        output.status.success(),
        "{what} failed:\n{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// Plans the single-object scene with a consumer binary; checks it solved.
fn plans(binary: &Path) {
    let run = ok(
        "the consumer",
        Command::new(binary)
            .args(["scenes/herb_single_object.yaml", "1"])
            .output(),
    );
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        stdout.starts_with("herb-single-object: solved in"),
        "{stdout}"
    );
}

#[test]
fn an_installed_pushplan_builds_with_cmake_and_with_pkg_config() {
    let work = std::env::temp_dir().join(format!("pushplan-install-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&work);
    // libpushplan.a lands next to the binary on a direct build of the library (with
    // --tests, the test build's own: nothing is built again).
    let mut build = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    build.args(["build", "--lib", "--tests"]);
    let binary = PathBuf::from(env!("CARGO_BIN_EXE_pushplan"));
    if binary.parent().is_some_and(|d| d.ends_with("release")) {
        build.arg("--release");
    }
    ok("cargo build --lib", build.output());
    let staged = work.join("staged");
    let out = ok(
        "pushplan install",
        Command::new(&binary)
            .args(["install", "--prefix"])
            .arg(&staged)
            .output(),
    );
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("installed"));
    // The installed archive is stripped of its debug sections: smaller than the built one.
    let built = binary
        .with_file_name("libpushplan.a")
        .metadata()
        .unwrap()
        .len();
    let installed = staged.join("lib/libpushplan.a").metadata().unwrap().len();
    assert!(
        installed < built,
        "installed {installed} bytes, built {built}: not stripped"
    );
    let prefix = work.join("prefix");
    std::fs::rename(&staged, &prefix).unwrap();
    for file in [
        "bin/pushplan",
        "lib/libpushplan.a",
        "include/pushplan/pushplan.h",
        "include/pushplan/ompl.h",
        "lib/pkgconfig/pushplan.pc",
        "lib/cmake/pushplan/pushplan-config.cmake",
        "lib/cmake/pushplan/pushplan-config-version.cmake",
        "share/pushplan/plan.schema.json",
    ] {
        assert!(prefix.join(file).is_file(), "{file} not installed");
    }
    let version = ok(
        "the installed CLI",
        Command::new(prefix.join("bin/pushplan"))
            .arg("--version")
            .output(),
    );
    assert!(String::from_utf8_lossy(&version.stdout).starts_with("pushplan "));

    // CMake: find_package(pushplan) and find_package(ompl) in one project.
    let cmake_build = work.join("cmake-build");
    let configure = ok(
        "cmake configure",
        Command::new("cmake")
            .args(["-S", "examples/cpp/cmake", "-B"])
            .arg(&cmake_build)
            .arg(format!("-DCMAKE_PREFIX_PATH={}", prefix.display()))
            .output(),
    );
    let log = String::from_utf8_lossy(&configure.stdout);
    assert!(log.contains("pushplan 0.1.0, OMPL 1."), "{log}");
    ok(
        "cmake build",
        Command::new("cmake")
            .arg("--build")
            .arg(&cmake_build)
            .output(),
    );
    plans(&cmake_build.join("plan_scene"));
    // A C++ program that links pushplan stays small (the library carries no debug info).
    let size = cmake_build.join("plan_scene").metadata().unwrap().len();
    assert!(size < 30 << 20, "plan_scene is {size} bytes");
    // The public OMPL layer with OMPL's planners: SST, KPIECE1 with a projection of the
    // application's own, and an ompl::tools::Benchmark of its own.
    // SST stops at its first solution: the time is only a bound, and with OMPL's seed set
    // the same plan comes back however loaded the machine is.
    let sst = || {
        let run = ok(
            "ompl_sst",
            Command::new(cmake_build.join("ompl_sst"))
                .args(["scenes/herb_single_object.yaml", "300"])
                .output(),
        );
        String::from_utf8_lossy(&run.stdout).into_owned()
    };
    let stdout = sst();
    assert!(
        stdout.contains("SST solved:") && stdout.contains("path valid"),
        "{stdout}"
    );
    assert_eq!(
        sst(),
        stdout,
        "SST with OMPL's seed set planned differently"
    );
    let kpiece = ok(
        "ompl_kpiece_projection",
        Command::new(cmake_build.join("ompl_kpiece_projection")).output(),
    );
    let stdout = String::from_utf8_lossy(&kpiece.stdout);
    assert!(stdout.contains("projection: solved"), "{stdout}");
    let log = work.join("own-benchmark.log");
    ok(
        "ompl_benchmark",
        Command::new(cmake_build.join("ompl_benchmark"))
            .arg("scenes/herb_single_object.yaml")
            .arg(&log)
            .args(["1", "1"])
            .output(),
    );
    let text = std::fs::read_to_string(&log).unwrap();
    assert!(
        text.contains("control_SST") && text.contains("control_KPIECE1"),
        "{text}"
    );

    // pkg-config, from the moved prefix.
    let flags = ok(
        "pkg-config",
        Command::new("pkg-config")
            .args(["--cflags", "--libs", "pushplan"])
            .env("PKG_CONFIG_PATH", prefix.join("lib/pkgconfig"))
            .output(),
    );
    let flags = String::from_utf8(flags.stdout).unwrap();
    assert!(!flags.contains("-std="), "{flags}");
    let consumer = work.join("plan_scene_pkg_config");
    ok(
        "g++ with pkg-config's flags",
        Command::new("g++")
            .arg("-o")
            .arg(&consumer)
            .arg("examples/cpp/plan_scene.cpp")
            .args(flags.split_whitespace())
            .output(),
    );
    plans(&consumer);
    let _ = std::fs::remove_dir_all(&work);
}
