//! Reading input files within stated limits, and how one file refers to another: regular files only (not `/dev/zero`, not a
//! folder, not a pipe), of bounded size, so that no input makes pushplan read until
//! memory runs out. The limits are documented in the README ("Input limits").

use std::io::Read;
use std::path::Path;

/// Largest scene file (bytes).
pub const MAX_SCENE_BYTES: u64 = 1 << 20;
/// Largest URDF (bytes).
pub const MAX_URDF_BYTES: u64 = 16 << 20;
/// Largest mesh file (bytes).
pub const MAX_MESH_BYTES: u64 = 64 << 20;
/// Largest plan file (bytes).
pub const MAX_PLAN_BYTES: u64 = 256 << 20;

/// The bytes of the regular file at `path`, if it has at most `max_bytes`. The error
/// says why, without the path (callers name the file).
pub fn read_bytes(path: &Path, max_bytes: u64) -> Result<Vec<u8>, String> {
    // Looked at before it is opened: opening a pipe (FIFO) waits for a writer, for ever.
    if let Some(why) = not_a_regular_file(path) {
        return Err(why);
    }
    // Opened without waiting all the same, should a pipe have taken the file's place since.
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    std::os::unix::fs::OpenOptionsExt::custom_flags(&mut options, libc::O_NONBLOCK);
    let file = options.open(path).map_err(|e| e.to_string())?;
    let metadata = file.metadata().map_err(|e| e.to_string())?;
    if !metadata.is_file() {
        return Err("not a regular file".into());
    }
    if metadata.len() > max_bytes {
        return Err(format!(
            "{} bytes; at most {max_bytes} are read",
            metadata.len()
        ));
    }
    // The size can change between the check and the read: read at most one byte more
    // than allowed, and refuse if that byte came.
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > max_bytes {
        return Err(format!("more than {max_bytes} bytes"));
    }
    Ok(bytes)
}

/// Why `path` is no regular file to read, in a few words ("not found", "a pipe (FIFO),
/// not a regular file", "a symbolic link loop"); `None` if it is one. Asks the file
/// system only: it opens nothing.
pub fn not_a_regular_file(path: &Path) -> Option<String> {
    match std::fs::metadata(path) {
        Ok(metadata) if metadata.is_file() => None,
        Ok(metadata) => {
            use std::os::unix::fs::FileTypeExt;
            let kind = metadata.file_type();
            let what = if kind.is_dir() {
                "a folder"
            } else if kind.is_fifo() {
                "a pipe (FIFO)"
            } else if kind.is_char_device() || kind.is_block_device() {
                "a device"
            } else {
                "a special file"
            };
            Some(format!("{what}, not a regular file"))
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            Some(match std::fs::symlink_metadata(path) {
                Ok(_) => "a symbolic link to nothing".into(),
                Err(_) => "not found".into(),
            })
        }
        Err(e) if e.raw_os_error() == Some(libc::ELOOP) => Some("a symbolic link loop".into()),
        Err(e) => Some(e.to_string()),
    }
}

/// As [`read_bytes`], as UTF-8 text.
pub fn read_text(path: &Path, max_bytes: u64) -> Result<String, String> {
    String::from_utf8(read_bytes(path, max_bytes)?).map_err(|_| "not UTF-8 text".into())
}

/// `message` with every double-quoted value longer than a few words cut short: parse
/// errors quote the offending value, and a file that is not what it claims to be (a
/// plan naming `/etc/passwd` as its scene) must not be printed in an error.
pub fn shorten_quoted(message: &str) -> String {
    const KEEP: usize = 40;
    let mut out = String::with_capacity(message.len().min(4 * KEEP));
    let mut rest = message;
    while let Some(open) = rest.find('"') {
        out.push_str(&rest[..=open]);
        rest = &rest[open + 1..];
        let close = rest.find('"').unwrap_or(rest.len());
        let quoted = &rest[..close];
        if quoted.chars().count() > KEEP {
            out.extend(quoted.chars().take(KEEP));
            out.push_str("...");
        } else {
            out.push_str(quoted);
        }
        rest = &rest[close..];
        if let Some(stripped) = rest.strip_prefix('"') {
            out.push('"');
            rest = stripped;
        }
    }
    out.push_str(rest);
    out
}

/// How a file in the folder `from` refers to `to`: the relative path between them (both
/// made absolute, `.` and `..` resolved by name), `/`-separated.
pub fn relative_path(from: &Path, to: &Path) -> Result<String, String> {
    use std::path::Component;
    let absolute = |p: &Path| std::path::absolute(p).map_err(|e| format!("{}: {e}", p.display()));
    let normal = |p: std::path::PathBuf| -> Vec<String> {
        let mut parts: Vec<String> = Vec::new();
        for c in p.components() {
            match c {
                Component::ParentDir => {
                    parts.pop();
                }
                Component::Normal(s) => parts.push(s.to_string_lossy().into_owned()),
                _ => {}
            }
        }
        parts
    };
    let (from, to) = (normal(absolute(from)?), normal(absolute(to)?));
    let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
    let mut parts: Vec<String> = vec!["..".into(); from.len() - common];
    parts.extend(to[common..].iter().cloned());
    Ok(parts.join("/"))
}

/// The member of the closed set `all` that `name_of` calls `name` (a command-line value,
/// a file's field); else an error naming `what` and every known name, in `all`'s order.
pub fn by_name<T: Copy>(
    all: &[T],
    name_of: impl Fn(T) -> &'static str,
    what: &str,
    name: &str,
) -> Result<T, String> {
    all.iter()
        .copied()
        .find(|&v| name_of(v) == name)
        .ok_or_else(|| {
            let known: Vec<&str> = all.iter().map(|&v| name_of(v)).collect();
            format!("unknown {what} '{name}' (known: {})", known.join(", "))
        })
}

/// Names for a message: the first ten, quoted, and how many more ("none" for none).
pub fn name_list<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let names: Vec<&str> = names.collect();
    if names.is_empty() {
        return "none".into();
    }
    let mut text: Vec<String> = names.iter().take(10).map(|n| format!("'{n}'")).collect();
    if names.len() > 10 {
        text.push(format!("and {} more", names.len() - 10));
    }
    text.join(", ")
}
