//! Builds the OMPL side (`cpp/`, public headers in `include/`) with cxx against the
//! system's OMPL and Eigen (and MuJoCo's world, `cpp/engines/`, against MuJoCo), and writes `pushplan.pc` (pkg-config) next to the built
//! library so C++ applications can link `libpushplan.a` from the build tree.
//!
//! OMPL and Eigen are found, in this order, from the environment
//! (`PUSHPLAN_OMPL_INCLUDE_DIR`, `PUSHPLAN_OMPL_LIB_DIR`, `PUSHPLAN_EIGEN_INCLUDE_DIR`),
//! from pkg-config (`ompl`, `eigen3`), then from the usual prefixes (`/usr/local`,
//! `/usr`, `/opt/ros/*`), so OMPL 1.5 from Debian, 1.6/1.7 from ROS or a source build
//! under `/usr/local` all work.

use std::path::{Path, PathBuf};
use std::process::Command;

const INSTALL: &str =
    "sudo apt-get install -y libompl-dev libeigen3-dev libmujoco-dev libfcl-dev ompl-demos";
/// The cxx bridges: the OMPL side's two halves, and MuJoCo's world.
const BRIDGES: [&str; 3] = [
    "src/bridge.rs",
    "src/bridge/entry.rs",
    "src/planning/execute/mujoco/bridge.rs",
];
const ENV_OMPL_INCLUDE: &str = "PUSHPLAN_OMPL_INCLUDE_DIR";
const ENV_OMPL_LIB: &str = "PUSHPLAN_OMPL_LIB_DIR";
const ENV_EIGEN_INCLUDE: &str = "PUSHPLAN_EIGEN_INCLUDE_DIR";

/// Where the C++ dependencies are.
struct Dependencies {
    /// The folder holding `ompl/control/SimpleSetup.h`.
    ompl_include: PathBuf,
    /// The folder holding `libompl`.
    ompl_lib: PathBuf,
    /// The folder holding `Eigen/Core`.
    eigen_include: PathBuf,
}

fn main() {
    for var in [
        ENV_OMPL_INCLUDE,
        ENV_OMPL_LIB,
        ENV_EIGEN_INCLUDE,
        "PKG_CONFIG_PATH",
    ] {
        println!("cargo:rerun-if-env-changed={var}");
    }
    let deps = match find_dependencies() {
        Ok(deps) => deps,
        Err(missing) => {
            eprintln!(
                "\npushplan needs {} (not found). Install them with:\n\n    {INSTALL}\n\n\
                 (or run `bash .ci/install-packages`). OMPL elsewhere: set {ENV_OMPL_INCLUDE} \
                 (the folder holding ompl/) and {ENV_OMPL_LIB}, or put its ompl.pc on \
                 PKG_CONFIG_PATH.\n",
                missing.join(", ")
            );
            std::process::exit(1);
        }
    };

    // Every C++ source under cpp/ (problem/, planners/*/, search/, api/), in a stable order.
    let mut sources = Vec::new();
    let mut folders = vec![PathBuf::from("cpp")];
    while let Some(dir) = folders.pop() {
        for path in std::fs::read_dir(&dir)
            .expect("cpp/ is readable")
            .filter_map(|e| e.ok().map(|e| e.path()))
        {
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|x| x == "cpp") {
                sources.push(path);
            }
        }
    }
    sources.sort();
    let twins = write_twins();
    let mut build = cxx_build::bridges(BRIDGES);
    build.files(&sources);
    build
        .include("include")
        .include(&twins)
        .include(&deps.ompl_include)
        .include(&deps.eigen_include)
        .std("c++17")
        .flag_if_supported("-Wno-deprecated-copy")
        .flag_if_supported("-Wno-unused-parameter")
        .compile("pushplan-cpp");
    if !linker_searches(&deps.ompl_lib) {
        println!("cargo:rustc-link-search=native={}", deps.ompl_lib.display());
    }
    println!("cargo:rustc-link-lib=ompl");
    // MuJoCo, the second engine of `pushplan execute` (Debian: libmujoco-dev).
    println!("cargo:rustc-link-lib=mujoco");
    for dir in ["cpp", "include"] {
        println!("cargo:rerun-if-changed={dir}");
    }
    for bridge in BRIDGES {
        println!("cargo:rerun-if-changed={bridge}");
    }
    write_pkg_config(&deps);
    write_install_manifest(&deps);
    // Debian's OMPL 1.5.2 defines OMPL_VERSION as "": benchmark logs take the version
    // from the numeric macros instead.
    println!(
        "cargo:rustc-env=PUSHPLAN_OMPL_VERSION={}",
        ompl_version(&deps.ompl_include)
    );
}

fn find_dependencies() -> Result<Dependencies, Vec<&'static str>> {
    let ompl_include = find_include(
        ENV_OMPL_INCLUDE,
        "ompl",
        "ompl/control/SimpleSetup.h",
        &ompl_prefix_candidates(),
    );
    let eigen_include = find_include(
        ENV_EIGEN_INCLUDE,
        "eigen3",
        "Eigen/Core",
        &[
            PathBuf::from("/usr/local/include/eigen3"),
            PathBuf::from("/usr/include/eigen3"),
        ],
    );
    let ompl_lib = ompl_include.as_ref().and_then(|inc| find_ompl_lib(inc));
    let mut missing = Vec::new();
    if ompl_include.is_none() {
        missing.push("OMPL headers");
    }
    if eigen_include.is_none() {
        missing.push("Eigen headers");
    }
    if ompl_include.is_some() && ompl_lib.is_none() {
        missing.push("the OMPL library");
    }
    // MuJoCo from Debian's libmujoco-dev (the headers and libmujoco.so on the usual paths).
    if !["/usr/include", "/usr/local/include"]
        .iter()
        .any(|dir| Path::new(dir).join("mujoco/mujoco.h").exists())
    {
        missing.push("MuJoCo (mujoco/mujoco.h)");
    }
    match (ompl_include, eigen_include, ompl_lib) {
        (Some(ompl_include), Some(eigen_include), Some(ompl_lib)) if missing.is_empty() => {
            Ok(Dependencies {
                ompl_include,
                ompl_lib,
                eigen_include,
            })
        }
        _ => Err(missing),
    }
}

/// The first folder holding `marker`: the environment variable, pkg-config's `-I`
/// folders of `package`, then `candidates`.
fn find_include(var: &str, package: &str, marker: &str, candidates: &[PathBuf]) -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os(var) {
        let dir = PathBuf::from(dir);
        if dir.join(marker).exists() {
            return Some(dir);
        }
        println!(
            "cargo:warning={var}={} holds no {marker}; looking elsewhere",
            dir.display()
        );
    }
    pkg_config(package, "--cflags-only-I")
        .iter()
        .filter_map(|flag| flag.strip_prefix("-I").map(PathBuf::from))
        .chain(candidates.iter().cloned())
        .find(|dir| dir.join(marker).exists())
}

/// `include/ompl-1.*` folders under the usual prefixes, newest first within each.
fn ompl_prefix_candidates() -> Vec<PathBuf> {
    let mut prefixes = vec![PathBuf::from("/usr/local"), PathBuf::from("/usr")];
    if let Ok(entries) = std::fs::read_dir("/opt/ros") {
        let mut ros: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        ros.sort();
        prefixes.extend(ros.into_iter().rev());
    }
    let mut out = Vec::new();
    for prefix in prefixes {
        let include = prefix.join("include");
        let mut versions: Vec<PathBuf> = std::fs::read_dir(&include)
            .map(|entries| {
                entries
                    .filter_map(|e| e.ok().map(|e| e.path()))
                    .filter(|p| {
                        p.file_name()
                            .and_then(|n| n.to_str())
                            .is_some_and(|n| n.starts_with("ompl-"))
                    })
                    .collect()
            })
            .unwrap_or_default();
        versions.sort();
        out.extend(versions.into_iter().rev());
        out.push(include);
    }
    out
}

/// The folder of `libompl`: the environment variable, pkg-config's `-L` folders, then
/// the `lib` folders of the prefix the headers came from and the system's.
fn find_ompl_lib(ompl_include: &Path) -> Option<PathBuf> {
    let holds = |dir: &Path| {
        ["libompl.so", "libompl.a", "libompl.dylib"]
            .iter()
            .any(|f| dir.join(f).exists())
    };
    if let Some(dir) = std::env::var_os(ENV_OMPL_LIB) {
        let dir = PathBuf::from(dir);
        if holds(&dir) {
            return Some(dir);
        }
        println!(
            "cargo:warning={ENV_OMPL_LIB}={} holds no libompl; looking elsewhere",
            dir.display()
        );
    }
    // include/ompl-1.x or include: the prefix is one or two levels up.
    let prefix = ompl_include
        .ancestors()
        .find(|p| p.file_name().is_some_and(|n| n == "include"))
        .and_then(Path::parent)
        .map(Path::to_path_buf);
    let mut candidates: Vec<PathBuf> = pkg_config("ompl", "--libs-only-L")
        .iter()
        .filter_map(|flag| flag.strip_prefix("-L").map(PathBuf::from))
        .collect();
    if let Some(prefix) = prefix {
        candidates.push(prefix.join("lib").join(multiarch()));
        candidates.push(prefix.join("lib"));
        candidates.push(prefix.join("lib64"));
    }
    candidates.extend(system_lib_dirs());
    candidates.into_iter().find(|d| holds(d))
}

fn multiarch() -> String {
    let arch = std::env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_else(|_| "x86_64".into());
    format!("{arch}-linux-gnu")
}

fn system_lib_dirs() -> Vec<PathBuf> {
    vec![
        PathBuf::from("/usr/lib").join(multiarch()),
        PathBuf::from("/usr/lib"),
        PathBuf::from("/usr/lib64"),
    ]
}

/// Does the linker look in `dir` without being told?
fn linker_searches(dir: &Path) -> bool {
    system_lib_dirs().iter().any(|d| d == dir)
}

/// The output of `pkg-config FLAG PACKAGE`, split on whitespace (empty if pkg-config or
/// the package is missing).
fn pkg_config(package: &str, flag: &str) -> Vec<String> {
    Command::new("pkg-config")
        .args([flag, package])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| {
            String::from_utf8_lossy(&o.stdout)
                .split_whitespace()
                .map(str::to_owned)
                .collect()
        })
        .unwrap_or_default()
}

/// `target/<profile>/pushplan.pc`, pointing at this checkout's headers and the library
/// built next to it (an installed copy gets a relocatable one: `pushplan install`). No
/// `-std` flag: the headers need C++17 or later, and the application chooses which.
fn write_pkg_config(deps: &Dependencies) {
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    // OUT_DIR is target/<profile>/build/pushplan-<hash>/out.
    let Some(profile_dir) = out.ancestors().nth(3) else {
        return;
    };
    let root = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let ompl_libdir = if linker_searches(&deps.ompl_lib) {
        String::new()
    } else {
        format!("-L{} ", deps.ompl_lib.display())
    };
    let pc = format!(
        "prefix={root}\nlibdir={}\nincludedir=${{prefix}}/include\n\nName: pushplan\n\
         Description: Whole-arm rearrangement planning by quasistatic pushing (OMPL)\n\
         Version: {}\nCflags: -I${{includedir}} -I{} -I{}\n\
         Libs: -L${{libdir}} -lpushplan {ompl_libdir}-lompl -lmujoco -lpthread -ldl -lm\n",
        profile_dir.display(),
        std::env::var("CARGO_PKG_VERSION").unwrap_or_default(),
        deps.eigen_include.display(),
        deps.ompl_include.display(),
    );
    let _ = std::fs::write(profile_dir.join("pushplan.pc"), pc);
}

/// `OUT_DIR/install_manifest.rs`, read by `src/install.rs`: every public header and the
/// data installed under share/pushplan (so an installed copy does not depend on this
/// checkout), and where OMPL and Eigen are (the installed library was built against them).
fn write_install_manifest(deps: &Dependencies) {
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let mut headers = Vec::new();
    let mut folders = vec![root.join("include")];
    while let Some(dir) = folders.pop() {
        for entry in std::fs::read_dir(&dir)
            .expect("include/ is readable")
            .flatten()
        {
            let path = entry.path();
            if path.is_dir() {
                folders.push(path);
            } else {
                headers.push(path);
            }
        }
    }
    headers.sort();
    let mut code = String::from(
        "/// The public headers: (path under the include folder, text).\n\
         pub const HEADERS: &[(&str, &str)] = &[\n",
    );
    for h in &headers {
        let relative = h
            .strip_prefix(root.join("include"))
            .expect("under include/");
        code += &format!(
            "    ({:?}, include_str!({:?})),\n",
            relative.display().to_string(),
            h.display().to_string()
        );
    }
    code += "];\n";
    code += "/// The data installed under share/pushplan: (path there, bytes).\n\
             pub const DATA: &[(&str, &[u8])] = &[\n";
    for folder in DATA_FOLDERS {
        println!("cargo:rerun-if-changed={}", root.join(folder).display());
    }
    for file in data_files(&root) {
        code += &format!(
            "    ({:?}, include_bytes!({:?})),\n",
            file.strip_prefix(&root)
                .expect("under the package root")
                .display()
                .to_string(),
            file.display().to_string()
        );
    }
    code += "];\n";
    code += &format!(
        "/// OMPL's headers as this build found them.\n\
         pub const OMPL_INCLUDE_DIR: &str = {:?};\n",
        deps.ompl_include.display().to_string(),
    );
    std::fs::write(out.join("install_manifest.rs"), code).expect("OUT_DIR is writable");
}

/// The folders `pushplan install` puts under `share/pushplan`: the scenes, the robots they
/// name, and the C++ examples, which run on the installed scenes without the checkout.
const DATA_FOLDERS: [&str; 3] = ["scenes", "robots", "examples/cpp"];

/// The files of [`DATA_FOLDERS`], sorted.
fn data_files(root: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for top in DATA_FOLDERS {
        let mut folders = vec![root.join(top)];
        while let Some(dir) = folders.pop() {
            let Ok(entries) = std::fs::read_dir(&dir) else {
                continue;
            };
            for path in entries.flatten().map(|e| e.path()) {
                if path.is_dir() {
                    folders.push(path);
                } else {
                    files.push(path);
                }
            }
        }
    }
    files.sort();
    files
}

/// OMPL's version from `ompl/config.h`'s OMPL_MAJOR/MINOR/PATCH_VERSION ("" if unreadable).
fn ompl_version(include: &Path) -> String {
    let config = include.join("ompl/config.h");
    println!("cargo:rerun-if-changed={}", config.display());
    let text = std::fs::read_to_string(&config).unwrap_or_default();
    let number = |name: &str| {
        text.lines().find_map(|l| {
            l.strip_prefix("#define ")?
                .strip_prefix(name)?
                .trim()
                .parse::<u32>()
                .ok()
        })
    };
    match (
        number("OMPL_MAJOR_VERSION"),
        number("OMPL_MINOR_VERSION"),
        number("OMPL_PATCH_VERSION"),
    ) {
        (Some(a), Some(b), Some(c)) => format!("{a}.{b}.{c}"),
        _ => String::new(),
    }
}

/// A Rust type the bridge passes as it is (`#[repr(C)]`), and its C++ twin, which
/// [`write_twins`] generates from the Rust declaration.
struct Twin {
    /// The file declaring it, from the package root.
    file: &'static str,
    /// Its name there.
    rust: &'static str,
    /// Its path from the root crate.
    path: &'static str,
    /// The twin's name in `pushplan::detail`.
    cpp: &'static str,
}

/// The twins; `PlannerKind` and `PathMetrics` are public C++ types (`pushplan.h`), written
/// by hand there.
const TWINS: [Twin; 5] = [
    Twin {
        file: "model/src/scene/file.rs",
        rust: "PlannerSpec",
        path: "crate::scene::PlannerParams",
        cpp: "PlannerParams",
    },
    Twin {
        file: "src/planning/run_settings.rs",
        rust: "RunSettings",
        path: "crate::planning::RunSettings",
        cpp: "RunSettings",
    },
    Twin {
        file: "src/planner/search.rs",
        rust: "ReachSettings",
        path: "crate::planner::ReachSettings",
        cpp: "ReachSettings",
    },
    Twin {
        file: "src/planner/search.rs",
        rust: "SearchProgress",
        path: "crate::planner::SearchProgress",
        cpp: "SearchProgress",
    },
    Twin {
        file: "src/planner/search.rs",
        rust: "SearchSummary",
        path: "crate::planner::SearchSummary",
        cpp: "SearchSummary",
    },
];

/// One field of a twin: its name, its C++ type, size (= alignment, bytes) and offset,
/// and its doc comment on one line.
struct Field {
    name: String,
    cpp_type: &'static str,
    size: usize,
    offset: usize,
    doc: String,
}

/// Writes `OUT_DIR/twins/pushplan/twins.h` (the C++ twins, the offsets each field must
/// have, and `PUSHPLAN_RUN_SETTINGS_FIELDS`, RunSettings's field names for C++'s
/// `Options`) and `OUT_DIR/twin_layout.rs` (the same offsets, asserted by the Rust
/// compiler), and returns the include folder.
///
/// Both sides are laid out by the C rule (each field at the next multiple of its
/// alignment); each compiler checks its own real layout against the offsets computed
/// here, so a type the bridge passes cannot differ between the two languages.
fn write_twins() -> PathBuf {
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    let pointer = std::env::var("CARGO_CFG_TARGET_POINTER_WIDTH")
        .ok()
        .and_then(|w| w.parse::<usize>().ok())
        .map_or(8, |bits| bits / 8);
    let mut header = String::from(
        "// Generated by build.rs from the Rust declarations: do not edit. The C++ twins of the\n\
         // Rust types the bridge passes as they are (#[repr(C)]): same fields, same order.\n\
         #pragma once\n\n#include \"pushplan/pushplan.h\"\n\n#include <cstddef>\n#include <cstdint>\n\n\
         namespace pushplan::detail\n{\n",
    );
    let mut rust = String::from("// Generated by build.rs: the layouts of the C++ twins.\n");
    for twin in &TWINS {
        println!("cargo:rerun-if-changed={}", twin.file);
        let text = std::fs::read_to_string(twin.file).expect("a twin's file is readable");
        let fields = twin_fields(&text, twin.rust, pointer)
            .unwrap_or_else(|why| panic!("{}: {}: {why}", twin.file, twin.rust));
        let size = fields.last().map_or(0, |f| f.offset + f.size);
        let align = fields.iter().map(|f| f.size).max().unwrap_or(1);
        let size = size.div_ceil(align) * align;
        header += &format!(
            "    /// Rust's `{}` ({}).\n    struct {}\n    {{\n",
            twin.rust, twin.file, twin.cpp
        );
        for f in &fields {
            header += &format!("        {} {};  ///< {}\n", f.cpp_type, f.name, f.doc);
        }
        header += "    };\n";
        header += &format!(
            "    static_assert(sizeof({}) == {size}, \"{} must have the layout of Rust's {}\");\n",
            twin.cpp, twin.cpp, twin.rust
        );
        rust += &format!(
            "const _: () = assert!(::core::mem::size_of::<{}>() == {size});\n",
            twin.path
        );
        for f in &fields {
            header += &format!(
                "    static_assert(offsetof({}, {}) == {}, \"{}::{} must lie where Rust's does\");\n",
                twin.cpp, f.name, f.offset, twin.cpp, f.name
            );
            rust += &format!(
                "const _: () = assert!(::core::mem::offset_of!({}, {}) == {});\n",
                twin.path, f.name, f.offset
            );
        }
        header += "\n";
        if twin.cpp == "RunSettings" {
            header +=
                "    /// X(field) for each field of RunSettings: `Options` has one of each name.\n";
            header += "#define PUSHPLAN_RUN_SETTINGS_FIELDS(X)";
            for f in &fields {
                header += &format!(" X({})", f.name);
            }
            header += "\n\n";
        }
    }
    header += "}  // namespace pushplan::detail\n";
    let include = out.join("twins");
    std::fs::create_dir_all(include.join("pushplan")).expect("OUT_DIR is writable");
    write_if_changed(&include.join("pushplan/twins.h"), &header);
    write_if_changed(&out.join("twin_layout.rs"), &rust);
    include
}

/// The fields of `pub struct name { ... }` in `text`, laid out by the C rule; an error
/// for a field type the twins do not know.
fn twin_fields(text: &str, name: &str, pointer: usize) -> Result<Vec<Field>, String> {
    let start = text
        .find(&format!("pub struct {name} {{"))
        .ok_or("no such struct")?;
    let body = &text[start..];
    let body =
        &body[body.find('{').expect("found above") + 1..body.find("\n}").ok_or("unclosed")?];
    let mut fields = Vec::new();
    let mut doc = String::new();
    let mut offset: usize = 0;
    for line in body.lines().map(str::trim) {
        if let Some(comment) = line.strip_prefix("///") {
            if !doc.is_empty() {
                doc.push(' ');
            }
            doc += comment.trim();
            continue;
        }
        let Some(field) = line.strip_prefix("pub ") else {
            continue;
        };
        let (field, ty) = field
            .split_once(':')
            .ok_or_else(|| format!("field `{line}`"))?;
        let ty = ty.trim().trim_end_matches(',');
        let (cpp_type, size) = match ty {
            "bool" => ("bool", 1),
            "PlannerKind" => ("PlannerKind", 1),
            "u32" => ("std::uint32_t", 4),
            "u64" => ("std::uint64_t", 8),
            "f64" => ("double", 8),
            "usize" => ("std::size_t", pointer),
            _ => return Err(format!("field `{field}`: no C++ twin for type `{ty}`")),
        };
        offset = offset.div_ceil(size) * size;
        fields.push(Field {
            name: field.trim().to_string(),
            cpp_type,
            size,
            offset,
            doc: std::mem::take(&mut doc),
        });
        offset += size;
    }
    Ok(fields)
}

/// Writes `text` unless the file holds it already (so C++ sources that include it are not
/// rebuilt for nothing).
fn write_if_changed(path: &Path, text: &str) {
    if std::fs::read_to_string(path).ok().as_deref() != Some(text) {
        std::fs::write(path, text).expect("OUT_DIR is writable");
    }
}
