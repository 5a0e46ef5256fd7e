//! Builds the OMPL side (`cpp/`, public headers in `include/`) with cxx against Debian's
//! OMPL 1.5.2 and Eigen, and writes `pushplan.pc` (pkg-config) next to the built library
//! so C++ applications can link `libpushplan.a`.

use std::path::{Path, PathBuf};

const OMPL_INCLUDE: &str = "/usr/include/ompl-1.5";
const EIGEN_INCLUDE: &str = "/usr/include/eigen3";
const INSTALL: &str = "sudo apt-get install -y libompl-dev libeigen3-dev libfcl-dev ompl-demos";

fn main() {
    let missing: Vec<&str> = [
        (
            Path::new(OMPL_INCLUDE).join("ompl/control/SimpleSetup.h"),
            "OMPL headers",
        ),
        (Path::new(EIGEN_INCLUDE).join("Eigen/Core"), "Eigen headers"),
        (
            PathBuf::from("/usr/lib/x86_64-linux-gnu/libompl.so"),
            "the OMPL library",
        ),
        (
            PathBuf::from("/usr/include/fcl/fcl.h"),
            "FCL headers (for the tests)",
        ),
    ]
    .iter()
    .filter(|(path, _)| !path.exists() && !alternative_exists(path))
    .map(|(_, what)| *what)
    .collect();
    if !missing.is_empty() {
        eprintln!("\npushplan needs {} (not found). Install them with:\n\n    {INSTALL}\n\n(or run `bash .ci/install-packages`)\n", missing.join(", "));
        std::process::exit(1);
    }

    // Every C++ source in cpp/, in a stable order.
    let mut sources: Vec<PathBuf> = std::fs::read_dir("cpp")
        .expect("cpp/ exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "cpp"))
        .collect();
    sources.sort();
    let mut build = cxx_build::bridge("src/ffi.rs");
    build.files(&sources);
    build
        .include("include")
        .include(OMPL_INCLUDE)
        .include(EIGEN_INCLUDE)
        .std("c++17")
        .flag_if_supported("-Wno-deprecated-copy")
        .flag_if_supported("-Wno-unused-parameter")
        .compile("pushplan-cpp");
    println!("cargo:rustc-link-lib=ompl");
    build_fcl_oracle();
    for dir in ["cpp", "include"] {
        println!("cargo:rerun-if-changed={dir}");
    }
    println!("cargo:rerun-if-changed=src/ffi.rs");
    write_pkg_config();
}

/// FCL, the independent oracle of the collision tests: linked into test binaries only,
/// so the library itself does not depend on FCL.
fn build_fcl_oracle() {
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    cxx_build::bridge("tests/fcl_oracle.rs")
        .file("tests/fcl_oracle.cpp")
        .include(EIGEN_INCLUDE)
        .std("c++17")
        .flag_if_supported("-Wno-unused-parameter")
        .cargo_metadata(false)
        .compile("pushplan-fcl-oracle");
    println!(
        "cargo:rustc-link-arg-tests={}",
        out.join("libpushplan-fcl-oracle.a").display()
    );
    println!("cargo:rustc-link-arg-tests=-lfcl");
    println!("cargo:rustc-link-arg-tests=-lccd");
    for file in [
        "tests/fcl_oracle.rs",
        "tests/fcl_oracle.cpp",
        "tests/fcl_oracle.h",
    ] {
        println!("cargo:rerun-if-changed={file}");
    }
}

/// Multi-arch library folders other than x86_64.
fn alternative_exists(path: &Path) -> bool {
    let name = path.file_name().unwrap_or_default();
    path.starts_with("/usr/lib")
        && ["/usr/lib/aarch64-linux-gnu", "/usr/lib"]
            .iter()
            .any(|d| Path::new(d).join(name).exists())
}

/// `target/<profile>/pushplan.pc`, pointing at this checkout's headers and library.
fn write_pkg_config() {
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    // OUT_DIR is target/<profile>/build/pushplan-<hash>/out.
    let Some(profile_dir) = out.ancestors().nth(3) else {
        return;
    };
    let root = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let pc = format!(
        "prefix={root}\nlibdir={}\nincludedir=${{prefix}}/include\n\nName: pushplan\nDescription: Whole-arm rearrangement planning by quasistatic pushing (OMPL)\nVersion: {}\nCflags: -std=c++17 -I${{includedir}} -I{EIGEN_INCLUDE} -I{OMPL_INCLUDE}\nLibs: ${{libdir}}/libpushplan.a -lompl -lpthread -ldl -lm\n",
        profile_dir.display(),
        std::env::var("CARGO_PKG_VERSION").unwrap_or_default()
    );
    let _ = std::fs::write(profile_dir.join("pushplan.pc"), pc);
}
