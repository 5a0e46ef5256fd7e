//! Compiles the FCL side of the oracle against the system's FCL (and the Eigen it uses),
//! found through pkg-config (Debian: `libfcl-dev`).

use std::process::Command;

fn main() {
    let flags = Command::new("pkg-config")
        .args(["--cflags-only-I", "fcl", "eigen3"])
        .output()
        .ok()
        .filter(|out| out.status.success())
        .unwrap_or_else(|| {
            eprintln!(
                "\nThe FCL oracle of pushplan's tests needs FCL and Eigen (pkg-config fcl eigen3). \
                 Install them with:\n\n    sudo apt-get install -y libfcl-dev libeigen3-dev\n\n\
                 (or run `bash .ci/install-packages`).\n"
            );
            std::process::exit(1);
        });
    let mut build = cxx_build::bridge("src/lib.rs");
    for dir in String::from_utf8_lossy(&flags.stdout)
        .split_whitespace()
        .filter_map(|f| f.strip_prefix("-I"))
    {
        build.include(dir);
    }
    build
        .file("src/fcl_oracle.cpp")
        .std("c++17")
        .flag_if_supported("-Wno-unused-parameter")
        .compile("pushplan-fcl-oracle");
    println!("cargo:rustc-link-lib=fcl");
    println!("cargo:rustc-link-lib=ccd");
    for file in ["src/lib.rs", "src/fcl_oracle.cpp", "src/fcl_oracle.h"] {
        println!("cargo:rerun-if-changed={file}");
    }
    println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
}
