//! Build script. The Rust model needs no native code; the OMPL side (`cpp/`, bridged
//! with cxx) is compiled here once it exists, against Debian's OMPL 1.5.2.
fn main() {
    println!("cargo:rerun-if-changed=build.rs");
}
