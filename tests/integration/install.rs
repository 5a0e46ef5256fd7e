//! `pushplan install` as a C++ user meets it: install into a prefix, move the prefix
//! (nothing may point back into the build or at this machine's system folders), then build
//! the installed C++ examples against it with CMake (`find_package(pushplan)` beside
//! `find_package(ompl)`; the shared and the static library; the C++ API and the public
//! OMPL layer with OMPL's SST, KPIECE1 and Benchmark) and with pkg-config, and run them on
//! the installed scenes. An OMPL of another version is refused by name; an installed
//! pushplan installs itself elsewhere.

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

/// Plans the installed single-object scene with a consumer binary; checks it solved.
fn plans(binary: &Path, scene: &Path) {
    let run = ok(
        "the consumer",
        Command::new(binary).arg(scene).arg("1").output(),
    );
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        stdout.starts_with("herb-single-object: solved in"),
        "{stdout}"
    );
}

#[test]
fn an_installed_pushplan_builds_with_cmake_and_with_pkg_config_from_anywhere() {
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
    // The shared library: a SONAME with the version, no debug sections.
    let readelf = |args: &[&str]| {
        let out = ok(
            "readelf",
            Command::new("readelf")
                .args(args)
                .arg(staged.join("lib/libpushplan.so"))
                .output(),
        );
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    assert!(
        readelf(&["-d"]).contains("Library soname: [libpushplan.so.0.1]"),
        "no SONAME"
    );
    assert!(!readelf(&["-S"]).contains(".debug_info"), "debug info");
    // Nothing installed for build systems names this machine's folders: the build, the
    // prefix or the system's (OMPL and Eigen are found as packages where the user is).
    let package_files = std::fs::read_dir(staged.join("lib/cmake/pushplan"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .chain([staged.join("lib/pkgconfig/pushplan.pc")]);
    for file in package_files {
        let text = std::fs::read_to_string(&file).unwrap();
        for path in [
            staged.to_str().unwrap(),
            env!("CARGO_MANIFEST_DIR"),
            "/usr/",
        ] {
            assert!(!text.contains(path), "{} names {path}", file.display());
        }
    }
    let prefix = work.join("prefix");
    std::fs::rename(&staged, &prefix).unwrap();
    let share = prefix.join("share/pushplan");
    for file in [
        "bin/pushplan",
        "lib/libpushplan.a",
        "lib/libpushplan.so",
        "include/pushplan/pushplan.h",
        "include/pushplan/ompl.h",
        "lib/pkgconfig/pushplan.pc",
        "lib/cmake/pushplan/pushplan-config.cmake",
        "lib/cmake/pushplan/pushplan-config-version.cmake",
        "lib/cmake/pushplan/pushplan-targets.cmake",
        "share/pushplan/plan.schema.json",
        "share/pushplan/robots/wam7.urdf",
        "share/pushplan/examples/cpp/plan_scene.cpp",
    ] {
        assert!(prefix.join(file).is_file(), "{file} not installed");
    }
    let scene = share.join("scenes/herb_single_object.yaml");
    let version = ok(
        "the installed CLI",
        Command::new(prefix.join("bin/pushplan"))
            .arg("--version")
            .output(),
    );
    assert!(String::from_utf8_lossy(&version.stdout).starts_with("pushplan "));
    // The installed CLI plans an installed scene (its robot found beside it).
    let plan = work.join("plan.json");
    ok(
        "the installed CLI's plan",
        Command::new(prefix.join("bin/pushplan"))
            .arg("plan")
            .arg(&scene)
            .args(["--seed", "1", "--threads", "1", "--quiet", "--out"])
            .arg(&plan)
            .output(),
    );

    // CMake: the installed examples, find_package(pushplan) and find_package(ompl) in one
    // project, from outside the checkout.
    let cmake_build = work.join("cmake-build");
    let configure = |build: &Path, extra: &[String]| {
        Command::new("cmake")
            .arg("-S")
            .arg(share.join("examples/cpp/cmake"))
            .arg("-B")
            .arg(build)
            .arg(format!("-DCMAKE_PREFIX_PATH={}", prefix.display()))
            .args(extra)
            .current_dir(&work)
            .output()
    };
    let configured = ok("cmake configure", configure(&cmake_build, &[]));
    let log = String::from_utf8_lossy(&configured.stdout);
    assert!(log.contains("pushplan 0.1.0, OMPL 1."), "{log}");
    ok(
        "cmake build",
        Command::new("cmake")
            .arg("--build")
            .arg(&cmake_build)
            .output(),
    );
    plans(&cmake_build.join("plan_scene"), &scene);
    plans(&cmake_build.join("plan_scene_static"), &scene);
    // A program on the shared library is small and loads it from the prefix.
    let size = cmake_build.join("plan_scene").metadata().unwrap().len();
    assert!(size < 1 << 20, "plan_scene is {size} bytes");
    let ldd = ok(
        "ldd",
        Command::new("ldd")
            .arg(cmake_build.join("plan_scene"))
            .output(),
    );
    let ldd = String::from_utf8_lossy(&ldd.stdout);
    assert!(
        ldd.contains(&format!(
            "libpushplan.so.0.1 => {}",
            prefix.join("lib").display()
        )),
        "{ldd}"
    );
    // The static one carries the library and no debug info of it.
    let size = cmake_build
        .join("plan_scene_static")
        .metadata()
        .unwrap()
        .len();
    assert!(size < 30 << 20, "plan_scene_static is {size} bytes");
    // The public OMPL layer with OMPL's planners: SST, KPIECE1 with a projection of the
    // application's own, and an ompl::tools::Benchmark of its own.
    // SST stops at its first solution: the time is only a bound, and with OMPL's seed set
    // the same plan comes back however loaded the machine is.
    let sst = || {
        let run = ok(
            "ompl_sst",
            Command::new(cmake_build.join("ompl_sst"))
                .arg(&scene)
                .arg("300")
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
        Command::new(cmake_build.join("ompl_kpiece_projection"))
            .arg(&scene)
            .output(),
    );
    let stdout = String::from_utf8_lossy(&kpiece.stdout);
    assert!(stdout.contains("projection: solved"), "{stdout}");
    let log = work.join("own-benchmark.log");
    ok(
        "ompl_benchmark",
        Command::new(cmake_build.join("ompl_benchmark"))
            .arg(&scene)
            .arg(&log)
            .args(["1", "1"])
            .output(),
    );
    let text = std::fs::read_to_string(&log).unwrap();
    assert!(
        text.contains("control_SST") && text.contains("control_KPIECE1"),
        "{text}"
    );

    // An OMPL of another version (here a package that says 1.6.0) is refused at
    // configure time, both versions named: not two OMPLs in one program.
    let other_ompl = work.join("other-ompl");
    std::fs::create_dir_all(&other_ompl).unwrap();
    std::fs::write(
        other_ompl.join("omplConfig.cmake"),
        "set(OMPL_VERSION 1.6.0)\nset(OMPL_INCLUDE_DIRS \"\")\nset(OMPL_LIBRARIES ompl)\n",
    )
    .unwrap();
    let refused = configure(
        &work.join("cmake-other-ompl"),
        &[format!("-Dompl_DIR={}", other_ompl.display())],
    )
    .unwrap();
    let log = String::from_utf8_lossy(&refused.stdout) + String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success(), "{log}");
    let log = log.split_whitespace().collect::<Vec<_>>().join(" "); // CMake wraps lines
    assert!(
        log.contains("built against OMPL 1.5") && log.contains("found OMPL 1.6.0"),
        "{log}"
    );

    // pkg-config, from the moved prefix: OMPL (the version built against) and Eigen come
    // from their own .pc files. Debian's ompl.pc adds -std=c++14, so C++17 goes after.
    let pkg_config = |args: &[&str]| {
        let out = ok(
            "pkg-config",
            Command::new("pkg-config")
                .args(args)
                .arg("pushplan")
                .env("PKG_CONFIG_PATH", prefix.join("lib/pkgconfig"))
                .output(),
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let requires = pkg_config(&["--print-requires"]);
    assert!(
        requires.contains("ompl = 1.5") && requires.contains("eigen3"),
        "{requires}"
    );
    assert!(pkg_config(&["--static", "--libs"]).contains("-lmujoco"));
    let flags = pkg_config(&["--cflags", "--libs"]);
    let consumer = work.join("plan_scene_pkg_config");
    ok(
        "g++ with pkg-config's flags",
        Command::new("g++")
            .arg("-o")
            .arg(&consumer)
            .arg(share.join("examples/cpp/plan_scene.cpp"))
            .args(flags.split_whitespace())
            .arg("-std=c++17")
            .output(),
    );
    let run = ok(
        "the pkg-config consumer",
        Command::new(&consumer)
            .arg(&scene)
            .arg("1")
            .env("LD_LIBRARY_PATH", prefix.join("lib"))
            .output(),
    );
    assert!(String::from_utf8_lossy(&run.stdout).starts_with("herb-single-object: solved in"));

    // The installed pushplan installs itself elsewhere (its archive is in its lib/).
    let again = work.join("again");
    ok(
        "the installed pushplan's install",
        Command::new(prefix.join("bin/pushplan"))
            .args(["install", "--prefix"])
            .arg(&again)
            .output(),
    );
    assert!(again.join("lib/libpushplan.so.0.1.0").is_file());
    assert!(again
        .join("share/pushplan/scenes/herb_single_object.yaml")
        .is_file());
    let _ = std::fs::remove_dir_all(&work);
}
