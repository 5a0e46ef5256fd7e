//! `pushplan install --prefix DIR`: the CLI, the static library, the public headers, a
//! pkg-config file and a CMake package, laid out as C++ build systems expect:
//!
//! ```text
//! DIR/bin/pushplan
//! DIR/lib/libpushplan.a
//! DIR/include/pushplan/...
//! DIR/lib/pkgconfig/pushplan.pc              (relocatable: paths from ${pcfiledir})
//! DIR/lib/cmake/pushplan/pushplan-config.cmake, pushplan-config-version.cmake
//! DIR/share/pushplan/plan.schema.json         (the plan files' JSON Schema)
//! ```
//!
//! The headers are compiled into the binary (an installed copy does not need the
//! checkout); the library is the `libpushplan.a` cargo built next to the binary, installed
//! without its debug sections (binutils' `strip --strip-debug`, where it is on the PATH):
//! Rust's standard library ships with debug info, which would otherwise be most of the
//! archive and of every program linked against it.

use std::path::{Path, PathBuf};

include!(concat!(env!("OUT_DIR"), "/install_manifest.rs"));

const CMAKE_CONFIG: &str = include_str!("../cpp/cmake/pushplan-config.cmake.in");
const CMAKE_VERSION: &str = include_str!("../cpp/cmake/pushplan-config-version.cmake.in");
const VERSION: &str = env!("CARGO_PKG_VERSION");
const PLAN_SCHEMA: &str = include_str!("../docs/plan.schema.json");

/// Installs into `prefix` the running `binary` and the `libpushplan.a` beside it.
/// Returns the files written.
pub fn install(prefix: &Path, binary: &Path) -> Result<Vec<PathBuf>, String> {
    let library = binary.with_file_name("libpushplan.a");
    if !library.is_file() {
        return Err(format!(
            "{}: not found next to the binary; install from a cargo build \
             (`cargo run --release -- install --prefix DIR`)",
            library.display()
        ));
    }
    let mut written = Vec::new();
    let mut put = |relative: &str, contents: Contents| -> Result<(), String> {
        let path = prefix.join(relative);
        let fail = |e: std::io::Error| format!("{}: {e}", path.display());
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(fail)?;
        }
        match contents {
            Contents::Text(text) => pushplan::output::write_whole(&path, text)?,
            Contents::Copy(from) => {
                // Renamed into place, not overwritten: the binary being installed may be
                // the one running (re-installing into the same prefix).
                pushplan::output::write_whole_with(&path, |temporary| {
                    std::fs::copy(from, temporary).map(drop)
                })
                .map_err(|e| format!("{e} (copying {})", from.display()))?;
            }
        }
        written.push(path);
        Ok(())
    };
    put("bin/pushplan", Contents::Copy(binary))?;
    put("lib/libpushplan.a", Contents::Copy(&library))?;
    strip_debug_sections(&prefix.join("lib/libpushplan.a"))?;
    for (path, text) in HEADERS {
        put(&format!("include/{path}"), Contents::Text(text.to_string()))?;
    }
    put("lib/pkgconfig/pushplan.pc", Contents::Text(pkg_config()))?;
    put(
        "lib/cmake/pushplan/pushplan-config.cmake",
        Contents::Text(fill(CMAKE_CONFIG)),
    )?;
    put(
        "lib/cmake/pushplan/pushplan-config-version.cmake",
        Contents::Text(fill(CMAKE_VERSION)),
    )?;
    put(
        "share/pushplan/plan.schema.json",
        Contents::Text(PLAN_SCHEMA.to_string()),
    )?;
    Ok(written)
}

/// Removes the debug sections of the installed `archive` in place. Without `strip` on the
/// PATH the archive stays as built (larger, and as usable); a `strip` that fails is an
/// error naming the file.
fn strip_debug_sections(archive: &Path) -> Result<(), String> {
    match std::process::Command::new("strip")
        .arg("--strip-debug")
        .arg(archive)
        .output()
    {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(format!("{}: strip: {e}", archive.display())),
        Ok(out) if out.status.success() => Ok(()),
        Ok(out) => Err(format!(
            "{}: strip --strip-debug failed: {}",
            archive.display(),
            String::from_utf8_lossy(&out.stderr).trim()
        )),
    }
}

enum Contents<'a> {
    Text(String),
    Copy(&'a Path),
}

/// The installed `pushplan.pc`: the prefix is found from the file's own folder, so the
/// tree can move; `-L -l` form, so build systems put it after the objects; no `-std`.
fn pkg_config() -> String {
    let ompl_dir = Path::new(OMPL_LIBRARY)
        .parent()
        .map(|d| d.display().to_string())
        .unwrap_or_default();
    format!(
        "prefix=${{pcfiledir}}/../..\nlibdir=${{prefix}}/lib\nincludedir=${{prefix}}/include\n\n\
         Name: pushplan\n\
         Description: Whole-arm rearrangement planning by quasistatic pushing (OMPL)\n\
         Version: {VERSION}\n\
         Cflags: -I${{includedir}} -I{EIGEN_INCLUDE_DIR} -I{OMPL_INCLUDE_DIR}\n\
         Libs: -L${{libdir}} -lpushplan -L{ompl_dir} -lompl -lmujoco -lpthread -ldl -lm\n"
    )
}

/// A CMake template with this build's version and dependency paths.
fn fill(template: &str) -> String {
    template
        .replace("@VERSION@", VERSION)
        .replace("@OMPL_INCLUDE_DIR@", OMPL_INCLUDE_DIR)
        .replace("@EIGEN_INCLUDE_DIR@", EIGEN_INCLUDE_DIR)
        .replace("@OMPL_LIBRARY@", OMPL_LIBRARY)
}
