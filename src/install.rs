//! `pushplan install --prefix DIR`: the CLI, the libraries, the public headers, a
//! pkg-config file, a CMake package and the data, laid out as C++ build systems expect:
//!
//! ```text
//! DIR/bin/pushplan
//! DIR/lib/libpushplan.a
//! DIR/lib/libpushplan.so -> libpushplan.so.0.1 -> libpushplan.so.0.1.0   (SONAME libpushplan.so.0.1)
//! DIR/include/pushplan/...
//! DIR/lib/pkgconfig/pushplan.pc              (Requires: ompl = VERSION, eigen3; relocatable)
//! DIR/lib/cmake/pushplan/pushplan-config.cmake, -config-version.cmake, -targets*.cmake
//! DIR/share/pushplan/scenes/..., robots/..., examples/cpp/...
//! DIR/share/pushplan/plan.schema.json         (the plan files' JSON Schema)
//! ```
//!
//! The headers and the data are compiled into the binary (an installed copy does not need
//! the checkout, and can install itself elsewhere); the static library is the
//! `libpushplan.a` cargo built next to the binary, or the installed one beside `bin/`,
//! installed without its debug sections (binutils' `strip --strip-debug`, where it is on
//! the PATH): Rust's standard library ships with debug info, which would otherwise be most
//! of the archive and of every program linked against it.
//!
//! The shared library and the CMake package come from CMake itself
//! (`cpp/cmake/CMakeLists.txt`, run here): the whole archive linked into
//! `libpushplan.so`, exported targets, a version file and a config file written with
//! CMake's package helpers, finding OMPL, Eigen and Threads as packages (no path of this
//! machine in them), and refusing an OMPL of another version than the one built against.

use std::path::{Path, PathBuf};
use std::process::Command;

include!(concat!(env!("OUT_DIR"), "/install_manifest.rs"));

const CMAKE_PROJECT: &str = include_str!("../cpp/cmake/CMakeLists.txt");
const CMAKE_CONFIG: &str = include_str!("../cpp/cmake/pushplan-config.cmake.in");
const PLAN_SCHEMA: &str = include_str!("../docs/plan.schema.json");
const VERSION: &str = env!("CARGO_PKG_VERSION");
/// The OMPL version the library was built against ("" where its headers do not say).
const OMPL_VERSION: &str = env!("PUSHPLAN_OMPL_VERSION");

/// Installs into `prefix` the running `binary`, the `libpushplan.a` beside it (or in the
/// `lib/` beside its `bin/`: an installed copy), the headers, the data, the pkg-config
/// file, and the shared library and CMake package CMake builds from them. Returns the
/// files written.
pub fn install(prefix: &Path, binary: &Path) -> Result<Vec<PathBuf>, String> {
    let library = static_library(binary)?;
    let mut written = Vec::new();
    let mut put = |relative: &str, contents: Contents| -> Result<(), String> {
        let path = prefix.join(relative);
        let fail = |e: std::io::Error| format!("{}: {e}", path.display());
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(fail)?;
        }
        match contents {
            Contents::Bytes(bytes) => pushplan::output::write_whole(&path, bytes)?,
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
        put(&format!("include/{path}"), Contents::Bytes(text.as_bytes()))?;
    }
    for (path, bytes) in DATA {
        put(&format!("share/pushplan/{path}"), Contents::Bytes(bytes))?;
    }
    put(
        "share/pushplan/plan.schema.json",
        Contents::Bytes(PLAN_SCHEMA.as_bytes()),
    )?;
    put(
        "lib/pkgconfig/pushplan.pc",
        Contents::Bytes(pkg_config().as_bytes()),
    )?;
    written.extend(cmake_package(prefix)?);
    Ok(written)
}

/// The `libpushplan.a` to install: cargo's, next to the binary, else an installed one in
/// the `lib/` beside the binary's `bin/`.
fn static_library(binary: &Path) -> Result<PathBuf, String> {
    let beside = binary.with_file_name("libpushplan.a");
    let installed = binary
        .parent()
        .and_then(Path::parent)
        .map(|prefix| prefix.join("lib/libpushplan.a"));
    [Some(beside.clone()), installed]
        .into_iter()
        .flatten()
        .find(|p| p.is_file())
        .ok_or_else(|| {
            format!(
                "{}: not found next to the binary, nor in the lib/ beside its bin/; install \
                 from a cargo build (`cargo run --release -- install --prefix DIR`) or from \
                 an installed pushplan",
                beside.display()
            )
        })
}

/// Removes the debug sections of the installed `archive` in place. Without `strip` on the
/// PATH the archive stays as built (larger, and as usable); a `strip` that fails is an
/// error naming the file.
fn strip_debug_sections(archive: &Path) -> Result<(), String> {
    match Command::new("strip")
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
    Bytes(&'a [u8]),
    Copy(&'a Path),
}

/// The installed `pushplan.pc`: the prefix is found from the file's own folder, so the
/// tree can move; OMPL (of the version built against) and Eigen come from their own
/// pkg-config files; `-lpushplan` takes the shared library, `--static` adds what the
/// archive needs besides.
fn pkg_config() -> String {
    let ompl = match OMPL_VERSION {
        "" => "ompl".to_string(),
        version => format!("ompl = {version}"),
    };
    format!(
        "prefix=${{pcfiledir}}/../..\nlibdir=${{prefix}}/lib\nincludedir=${{prefix}}/include\n\n\
         Name: pushplan\n\
         Description: Whole-arm rearrangement planning by quasistatic pushing (OMPL)\n\
         Version: {VERSION}\n\
         Requires: {ompl}, eigen3\n\
         Cflags: -I${{includedir}}\n\
         Libs: -L${{libdir}} -lpushplan\n\
         Libs.private: -lmujoco -lpthread -ldl -lm\n"
    )
}

/// Builds and installs `libpushplan.so` and the CMake package with CMake, from the
/// archive already in `prefix`: the files CMake installed.
fn cmake_package(prefix: &Path) -> Result<Vec<PathBuf>, String> {
    let prefix = prefix
        .canonicalize()
        .map_err(|e| format!("{}: {e}", prefix.display()))?;
    let work = std::env::temp_dir().join(format!("pushplan-cmake-{}", std::process::id()));
    let (source, build) = (work.join("source"), work.join("build"));
    let result = (|| {
        std::fs::create_dir_all(&source).map_err(|e| format!("{}: {e}", source.display()))?;
        for (name, text) in [
            ("CMakeLists.txt", CMAKE_PROJECT),
            ("pushplan-config.cmake.in", CMAKE_CONFIG),
        ] {
            pushplan::output::write_whole(&source.join(name), text)?;
        }
        // OMPL is looked for first where the library found it when it was built.
        let ompl_prefix = Path::new(OMPL_INCLUDE_DIR)
            .parent()
            .and_then(Path::parent)
            .unwrap_or(Path::new("/usr"));
        cmake(&[
            "-S".as_ref(),
            source.as_os_str(),
            "-B".as_ref(),
            build.as_os_str(),
            "-DCMAKE_BUILD_TYPE=Release".as_ref(),
            format!("-DCMAKE_INSTALL_PREFIX={}", prefix.display()).as_ref(),
            format!("-DCMAKE_PREFIX_PATH={}", ompl_prefix.display()).as_ref(),
            format!(
                "-DPUSHPLAN_ARCHIVE={}",
                prefix.join("lib/libpushplan.a").display()
            )
            .as_ref(),
            format!("-DPUSHPLAN_VERSION={VERSION}").as_ref(),
            format!("-DPUSHPLAN_OMPL_VERSION={OMPL_VERSION}").as_ref(),
        ])?;
        cmake(&["--build".as_ref(), build.as_os_str()])?;
        cmake(&["--install".as_ref(), build.as_os_str(), "--strip".as_ref()])?;
        let manifest = build.join("install_manifest.txt");
        let listed = std::fs::read_to_string(&manifest)
            .map_err(|e| format!("{}: {e}", manifest.display()))?;
        Ok(listed.lines().map(PathBuf::from).collect())
    })();
    let _ = std::fs::remove_dir_all(&work);
    result
}

/// Runs `cmake ARGS`; an error with the end of its output when it fails.
fn cmake(args: &[&std::ffi::OsStr]) -> Result<(), String> {
    let out = Command::new("cmake").args(args).output().map_err(|e| {
        format!(
            "cmake: {e}; `pushplan install` builds libpushplan.so and the CMake package with \
             CMake (Debian: apt install cmake)"
        )
    })?;
    if out.status.success() {
        return Ok(());
    }
    let text = String::from_utf8_lossy(&out.stdout) + String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = text.lines().collect();
    Err(format!(
        "cmake {} failed (the shared library and the CMake package):\n{}",
        args.first().map_or("".into(), |a| a.to_string_lossy()),
        lines[lines.len().saturating_sub(15)..].join("\n")
    ))
}
