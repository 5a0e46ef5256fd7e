//! Collision meshes: STL files become the convex hull of their vertices (one hull per
//! mesh; convex queries are an order of magnitude faster than triangle soups).

use crate::collision::Primitive;
use crate::error::{Error, Result};
use nalgebra::Point3;
use std::path::{Path, PathBuf};

/// Resolves a URDF mesh reference (`package://pkg/rel`, `file:///abs` or a relative path)
/// without ROS: `package://pkg` is searched for as a folder named `pkg` next to the URDF
/// and in each folder above it, then in the folders listed in `ROS_PACKAGE_PATH`.
pub fn resolve_mesh_path(filename: &str, urdf_path: &Path) -> Option<PathBuf> {
    let urdf_dir = urdf_path.parent().unwrap_or(Path::new("."));
    if let Some(rest) = filename.strip_prefix("package://") {
        let (package, relative) = rest.split_once('/')?;
        let mut roots: Vec<PathBuf> = urdf_dir.ancestors().map(Path::to_path_buf).collect();
        if let Some(paths) = std::env::var_os("ROS_PACKAGE_PATH") {
            roots.extend(std::env::split_paths(&paths));
        }
        return roots.iter().find_map(|root| {
            // Either the root holds the package folder, or the root is the package itself.
            let inside = root.join(package).join(relative);
            let itself = root.join(relative);
            if inside.is_file() {
                Some(inside)
            } else if root.file_name().is_some_and(|n| n == package) && itself.is_file() {
                Some(itself)
            } else {
                None
            }
        });
    }
    let path = match filename.strip_prefix("file://") {
        Some(abs) => PathBuf::from(abs),
        None => urdf_dir.join(filename),
    };
    path.is_file().then_some(path)
}

/// Reads an STL mesh (binary or ASCII), scales it and returns its convex hull as a primitive.
pub fn load_convex_mesh(path: &Path, scale: [f64; 3]) -> Result<Primitive> {
    let mesh_error = |message: String| Error::Mesh {
        file: path.to_path_buf(),
        message,
    };
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if extension.as_deref() != Some("stl") {
        return Err(mesh_error("only STL meshes are supported".into()));
    }
    let bytes = crate::input::read_bytes(path, crate::input::MAX_MESH_BYTES)
        .map_err(|message| Error::io(path, message))?;
    let mesh = stl_io::read_stl(&mut std::io::Cursor::new(bytes))
        .map_err(|e| mesh_error(e.to_string()))?;
    let points: Vec<Point3<f64>> = mesh
        .vertices
        .iter()
        .map(|v| {
            Point3::new(
                v.0[0] as f64 * scale[0],
                v.0[1] as f64 * scale[1],
                v.0[2] as f64 * scale[2],
            )
        })
        .collect();
    if points.len() < 4
        || points
            .iter()
            .any(|p| !p.coords.iter().all(|c| c.is_finite()))
    {
        return Err(mesh_error(
            "needs at least 4 finite vertices to make a solid".into(),
        ));
    }
    Ok(Primitive::ConvexHull { points })
}
