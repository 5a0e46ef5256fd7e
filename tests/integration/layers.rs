//! The layers hold: every path in `src/` names a module of its own layer or of a layer
//! below it (`crate::` in the library, `pushplan::` in the binary's `cli` and `install`).
//! The model is a crate of its own (`model/`), so the compiler keeps it below everything
//! here; this test keeps the order above it:
//!
//! model < planning < planner (the search's side) < bridge < render, benchmark
//! (the library) < install, cli (the binary).
//!
//! Nothing names the bridge but the bridge: the applications call the search through
//! `planner::Search`, and `main.rs`, which assembles the layers, hands them the bridge's.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The modules each part of `src/` may name through `crate::`, beside the model's and its
/// own: the layers below it, the bridge excepted.
const LAYERS: &[(&str, &[&str])] = &[
    ("planning", &[]),
    ("planner", &["planning"]),
    ("bridge", &["planning", "planner"]),
    ("render", &["planning"]),
    ("benchmark", &["planning"]),
    ("install", &[]),
    (
        "cli",
        &["planning", "planner", "render", "benchmark", "install"],
    ),
];

/// The model's modules (its `lib.rs`), which the root crate re-exports under the same
/// names.
fn model_modules() -> BTreeSet<String> {
    std::fs::read_to_string(root().join("model/src/lib.rs"))
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod ")?.strip_suffix(';'))
        .map(str::to_string)
        .collect()
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(rust_files(&path));
        } else if path.extension().is_some_and(|x| x == "rs") {
            files.push(path);
        }
    }
    files
}

/// The binary's layers: they name the library's modules as `pushplan::`.
const BINARY: &[&str] = &["install", "cli"];

/// The first segment of every `crate::` path in `text`.
fn crate_modules(text: &str) -> BTreeSet<String> {
    paths_below("crate::", text)
}

/// The first segment of every path in `text` that starts with `prefix` (`crate::`).
fn paths_below(prefix: &str, text: &str) -> BTreeSet<String> {
    text.match_indices(prefix)
        .filter(|(at, _)| {
            // `crate::` itself, not the end of another name (`pushplan_crate::`).
            !text[..*at].ends_with(|c: char| c.is_alphanumeric() || c == '_')
        })
        .map(|(at, m)| {
            text[at + m.len()..]
                .chars()
                .take_while(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || *c == '_')
                .collect()
        })
        .filter(|name: &String| !name.is_empty())
        .collect()
}

/// The layer a file of `src/` belongs to: its top-level module.
fn layer_of(file: &Path) -> String {
    let relative = file.strip_prefix(root().join("src")).unwrap();
    let first = relative.components().next().unwrap().as_os_str();
    Path::new(first)
        .file_stem()
        .unwrap()
        .to_string_lossy()
        .into_owned()
}

#[test]
fn no_module_imports_a_layer_above_its_own() {
    let model = model_modules();
    assert!(
        model.contains("scene") && model.contains("propagate"),
        "{model:?}"
    );
    let mut upward = Vec::new();
    let mut checked = 0;
    for file in rust_files(&root().join("src")) {
        let layer = layer_of(&file);
        let Some((_, below)) = LAYERS.iter().find(|(name, _)| *name == layer) else {
            continue; // lib.rs, main.rs: they assemble the layers
        };
        checked += 1;
        let text = std::fs::read_to_string(&file).unwrap();
        let mut modules = crate_modules(&text);
        if BINARY.contains(&layer.as_str()) {
            modules.extend(paths_below("pushplan::", &text));
        }
        for module in modules {
            let allowed =
                module == layer || model.contains(&module) || below.contains(&module.as_str());
            if !allowed {
                upward.push(format!(
                    "{}: crate::{module} ({layer} may name {below:?} and the model)",
                    file.strip_prefix(root()).unwrap().display()
                ));
            }
        }
    }
    assert!(checked > 50, "only {checked} files checked");
    assert!(upward.is_empty(), "upward imports:\n{}", upward.join("\n"));
}

#[test]
fn every_part_of_src_has_a_layer() {
    let mut parts: BTreeSet<String> = rust_files(&root().join("src"))
        .iter()
        .map(|f| layer_of(f))
        .collect();
    parts.remove("lib");
    parts.remove("main");
    let layered: BTreeSet<String> = LAYERS.iter().map(|(n, _)| n.to_string()).collect();
    assert_eq!(
        parts, layered,
        "a new top-level module needs a place in LAYERS"
    );
}

#[test]
fn the_model_crate_depends_on_neither_cxx_nor_the_planner() {
    // What the model's code may name, the compiler holds through this list.
    let manifest = std::fs::read_to_string(root().join("model/Cargo.toml")).unwrap();
    let dependencies: Vec<&str> = manifest
        .lines()
        .map(str::trim)
        .filter(|l| !l.starts_with('#') && !l.starts_with('[') && l.contains('='))
        .map(|l| l.split('=').next().unwrap().trim())
        .collect();
    assert!(dependencies.contains(&"nalgebra"), "{dependencies:?}");
    for forbidden in ["cxx", "cxx-build", "pushplan"] {
        assert!(
            !dependencies.contains(&forbidden),
            "model/Cargo.toml depends on {forbidden}"
        );
    }
}

#[test]
fn the_scan_finds_what_it_looks_for() {
    let found =
        crate_modules("use crate::planning::path;\nlet x = crate::bridge::solve(); my_crate::no");
    assert_eq!(
        found,
        ["bridge", "planning"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    );
}

/// Every package of the workspace's build, with its features, as `cargo tree` lists it
/// over the given dependency kinds.
fn packages_with_features(kinds: &str) -> BTreeSet<String> {
    let tree =
        std::process::Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
            .current_dir(root())
            .args([
                "tree",
                "--offline",
                "-p",
                "pushplan",
                "-p",
                "pushplan-model",
                "-e",
                kinds,
            ])
            .args(["-f", "{p} {f}", "--prefix", "none"])
            .output()
            .unwrap();
    assert!(
        tree.status.success(),
        "{}",
        String::from_utf8_lossy(&tree.stderr)
    );
    String::from_utf8_lossy(&tree.stdout)
        .lines()
        .map(|l| l.trim_end_matches(" (*)").to_string())
        .collect()
}

#[test]
fn the_test_build_reuses_the_release_builds_dependencies() {
    // The dev-dependencies may add packages, not features of the packages a plain build
    // has: `cargo test --release` then builds none of them again.
    let plain = packages_with_features("normal,build");
    let with_dev = packages_with_features("normal,build,dev");
    let changed: Vec<&String> = plain.difference(&with_dev).collect();
    assert!(plain.len() > 50, "{plain:?}");
    assert!(
        changed.is_empty(),
        "features the dev-dependencies change (add them to [dependencies]): {changed:?}"
    );
}

/// The functions of each type the bridge declares (`extern "Rust"` in `src/bridge.rs`): a
/// method's type, an associated function's `#[Self]`, or a free function's first
/// argument's type.
fn bridge_functions() -> std::collections::BTreeMap<String, Vec<String>> {
    let text = std::fs::read_to_string(root().join("src/bridge.rs")).unwrap();
    let block = &text[text
        .find("extern \"Rust\" {")
        .expect("the bridge's Rust side")..];
    let block = &block[..block.find("\n    }\n").expect("its end")];
    let mut owners = std::collections::BTreeMap::<String, Vec<String>>::new();
    let mut self_type: Option<String> = None;
    for declaration in block.split(';') {
        for line in declaration.lines().map(str::trim) {
            if let Some(name) = line
                .strip_prefix("#[Self = \"")
                .and_then(|l| l.strip_suffix("\"]"))
            {
                self_type = Some(name.to_string());
            }
        }
        let Some(at) = declaration.find("fn ") else {
            continue;
        };
        let signature: String = declaration[at + 3..].split_whitespace().collect();
        let (name, rest) = signature.split_once('(').unwrap();
        let first = rest.split([',', ')']).next().unwrap_or("");
        let owner = self_type.take().unwrap_or_else(|| {
            let ty = first.split(':').nth(1).unwrap_or("free");
            ty.trim_start_matches('&')
                .trim_start_matches("mut")
                .to_string()
        });
        owners.entry(owner).or_default().push(name.to_string());
    }
    owners
}

#[test]
fn no_type_of_the_bridge_has_more_than_ten_functions() {
    let owners = bridge_functions();
    for ty in [
        "Problem",
        "Propagator",
        "ValidityChecker",
        "Metric",
        "NearestTree",
        "Goal",
        "Projection",
        "Finisher",
        "Darrt",
        "Grasping",
    ] {
        assert!(owners.contains_key(ty), "{ty} is not in {owners:?}");
    }
    let wide: Vec<_> = owners.iter().filter(|(_, fns)| fns.len() > 10).collect();
    assert!(
        wide.is_empty(),
        "types with more than ten functions: {wide:?}"
    );
    // The scan counts what is there: the propagator's calls are all found.
    assert_eq!(
        owners["Propagator"],
        [
            "new",
            "propagate",
            "set_time_limit",
            "past_time_limit",
            "steps",
            "seconds",
            "search_stats"
        ]
    );
}
