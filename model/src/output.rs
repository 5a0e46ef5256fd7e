//! Writing output files whole or not at all. Every file pushplan writes (plans, reports,
//! pictures, benchmark logs and databases) goes first to a temporary file in the same
//! folder, is flushed to the disk, and only then renamed over the old one: a full disk,
//! a file-size limit or a crash leaves the previous file as it was, never a truncated
//! one, and a reader sees the old file or the new one, whole.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Writes `contents` to `path` whole or not at all. On failure the file at `path`, if
/// there was one, is unchanged, no temporary file is left behind, and the error names
/// `path` and says so. A file replaced keeps the permissions it had.
pub fn write_whole(path: &Path, contents: impl AsRef<[u8]>) -> Result<(), String> {
    let permissions = std::fs::metadata(path).ok().map(|m| m.permissions());
    write_whole_with(path, |temporary| {
        let mut file = new_file(temporary)?;
        file.write_all(contents.as_ref())?;
        if let Some(permissions) = permissions {
            file.set_permissions(permissions)?;
        }
        Ok(())
    })
}

/// As [`write_whole`], for a file that `write` makes at the temporary path it is given
/// (a copy, another program's output).
pub fn write_whole_with(
    path: &Path,
    write: impl FnOnce(&Path) -> std::io::Result<()>,
) -> Result<(), String> {
    let failed = |why: String| {
        format!(
            "{}: cannot write ({why}); {}",
            path.display(),
            match path.is_file() {
                true => "the previous file is left as it was",
                false => "nothing was written",
            }
        )
    };
    if path.is_dir() {
        return Err(failed("a folder is in the way".into()));
    }
    let temporary = temporary_beside(path);
    let written = write(&temporary)
        // On the disk before the rename: a crash after it must not leave an empty file.
        .and_then(|()| std::fs::File::open(&temporary)?.sync_all())
        .and_then(|()| std::fs::rename(&temporary, path));
    written.map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        failed(e.to_string())
    })
}

/// A file made anew at `path` (an error if one is there).
fn new_file(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)
}

/// Checks, before long work, that a file can be written at `path`: its folder (made if
/// missing) takes a new file, and `path` is not a folder. Writes nothing that stays.
pub fn check_writable(path: &Path) -> Result<(), String> {
    let folder = folder_of(path);
    std::fs::create_dir_all(&folder)
        .map_err(|e| format!("{}: cannot make the folder: {e}", folder.display()))?;
    if path.is_dir() {
        return Err(format!("{}: a folder, not a file to write", path.display()));
    }
    let probe = temporary_beside(path);
    new_file(&probe).map_err(|e| {
        format!(
            "{}: cannot write in {}: {e}",
            path.display(),
            folder.display()
        )
    })?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// The folder `path` is in (`.` for a bare file name).
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// A name for a temporary file beside `path`, unique in this process and across
/// processes (the process id), hidden (a leading dot) so that folder listings and globs
/// such as `*.log` pass over it.
fn temporary_beside(path: &Path) -> PathBuf {
    static COUNT: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let n = COUNT.fetch_add(1, Ordering::Relaxed);
    folder_of(path).join(format!(".{name}.{}.{n}.tmp", std::process::id()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("pushplan-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_file_is_replaced_whole_and_no_temporary_file_stays() {
        let dir = folder("replace");
        let path = dir.join("plan.json");
        write_whole(&path, "old").unwrap();
        write_whole(&path, "new contents").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new contents");
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(names.len(), 1, "only the file itself: {names:?}");
    }

    #[test]
    fn a_folder_in_the_way_is_named_and_left_alone() {
        let dir = folder("in-the-way");
        let path = dir.join("out.json");
        std::fs::create_dir(&path).unwrap();
        let e = write_whole(&path, "x").unwrap_err();
        assert!(e.contains("out.json") && e.contains("folder"), "{e}");
        assert!(path.is_dir());
        let e = check_writable(&path).unwrap_err();
        assert!(e.contains("a folder"), "{e}");
    }

    #[test]
    fn a_missing_folder_is_made_by_the_check() {
        let dir = folder("check");
        let path = dir.join("a/b/plan.json");
        check_writable(&path).unwrap();
        assert!(dir.join("a/b").is_dir());
        assert_eq!(std::fs::read_dir(dir.join("a/b")).unwrap().count(), 0);
    }
}
