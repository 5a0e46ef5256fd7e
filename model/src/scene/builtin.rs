//! Files built into the binary — the default scene and the WAM it uses — so that `plan`
//! without a scene and `scenes generate` work wherever the binary is, not only beside the
//! source tree it was built from.

use std::path::{Path, PathBuf};

/// The default scene's file name: the whole-arm paper's Fig. 1 situation.
pub const DEFAULT_SCENE: &str = "herb_fig1_clutter.yaml";
/// The robot of the default scene and of generated scenes.
pub const WAM: &str = "wam7.urdf";

const DEFAULT_SCENE_TEXT: &str = include_str!("../../../scenes/herb_fig1_clutter.yaml");
const WAM_TEXT: &str = include_str!("../../../robots/wam7.urdf");

/// Where built-in files are written for use: `$XDG_CACHE_HOME/pushplan/VERSION`, else
/// `$HOME/.cache/pushplan/VERSION`, else `pushplan-VERSION` in the system's temp folder.
pub fn cache_root() -> PathBuf {
    let version = env!("CARGO_PKG_VERSION");
    let absolute = |var: &str| {
        std::env::var_os(var)
            .map(PathBuf::from)
            .filter(|p| p.is_absolute())
    };
    absolute("XDG_CACHE_HOME")
        .or_else(|| absolute("HOME").map(|home| home.join(".cache")))
        .map(|cache| cache.join("pushplan").join(version))
        .unwrap_or_else(|| std::env::temp_dir().join(format!("pushplan-{version}")))
}

/// Writes the default scene and its robot under `root` as they sit in the source tree
/// (`scenes/`, `robots/`: the scene names its URDF relative to itself), unless identical
/// files are there already; returns the scene's path.
pub fn write_default_scene(root: &Path) -> Result<PathBuf, String> {
    write_if_different(&root.join("robots").join(WAM), WAM_TEXT)?;
    let scene = root.join("scenes").join(DEFAULT_SCENE);
    write_if_different(&scene, DEFAULT_SCENE_TEXT)?;
    Ok(scene)
}

/// The URDF `file` (built in as `text`) that scenes generated into `dir` name:
/// `robots/FILE` in `dir` or in the nearest folder above it that has one identical to the
/// built-in (a project's own tree), else the built-in copy written to `dir/robots/FILE`.
pub fn robot_file_for(dir: &Path, file: &str, text: &str) -> Result<PathBuf, String> {
    let dir = std::path::absolute(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let found = dir
        .ancestors()
        .map(|a| a.join("robots").join(file))
        .find(|p| std::fs::read_to_string(p).is_ok_and(|old| old == text));
    match found {
        Some(path) => Ok(path),
        None => {
            let path = dir.join("robots").join(file);
            write_if_different(&path, text)?;
            Ok(path)
        }
    }
}

/// The WAM URDF that scenes generated into `dir` name ([`robot_file_for`]).
pub fn wam_for(dir: &Path) -> Result<PathBuf, String> {
    robot_file_for(dir, WAM, WAM_TEXT)
}

/// Writes `text` to `path` unless the file holds it already ([`crate::output::write_whole`]:
/// a concurrent reader sees the old file or the new one, whole).
fn write_if_different(path: &Path, text: &str) -> Result<(), String> {
    if std::fs::read_to_string(path).is_ok_and(|old| old == text) {
        return Ok(());
    }
    let folder = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    crate::output::write_whole(path, text)
}
