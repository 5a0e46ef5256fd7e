//! Collision meshes: STL, OBJ and COLLADA files become convex hulls (convex queries are an
//! order of magnitude faster than triangle soups), each simplified to a few dozen vertices
//! within half a millimetre. A link's mesh is one hull when it is nearly convex, and a few
//! (an approximate convex decomposition, V-HACD) when its hull would add much volume the
//! mesh does not enclose: a robot's torso or pedestal, whose hull swallows the space its
//! own arms move through. Obstacles keep one hull.

use crate::collision::Primitive;
use crate::error::{Error, Result};
use nalgebra::Point3;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::ConvexPolyhedron;
use parry3d_f64::transformation::vhacd::{VHACDParameters, VHACD};
use std::cmp::Ordering;
use std::collections::hash_map::DefaultHasher;
use std::collections::{BinaryHeap, HashMap, HashSet};
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Resolves a URDF mesh reference (`package://pkg/rel`, `file:///abs` or a relative path)
/// without ROS: `package://pkg` is searched for as a folder named `pkg` next to the URDF
/// and in each folder above it, then in the folders listed in `ROS_PACKAGE_PATH`. The
/// error says where it looked, and why a file found there is not one to read (a pipe, a
/// device, a symbolic link loop).
pub fn resolve_mesh_path(filename: &str, urdf_path: &Path) -> std::result::Result<PathBuf, String> {
    let urdf_dir = urdf_path.parent().unwrap_or(Path::new("."));
    let candidates: Vec<PathBuf> = if let Some(rest) = filename.strip_prefix("package://") {
        let Some((package, relative)) = rest.split_once('/') else {
            return Err("a package:// reference needs a package and a path in it".into());
        };
        let mut roots: Vec<PathBuf> = urdf_dir.ancestors().map(Path::to_path_buf).collect();
        if let Some(paths) = std::env::var_os("ROS_PACKAGE_PATH") {
            roots.extend(std::env::split_paths(&paths));
        }
        // Either the root holds the package folder, or the root is the package itself.
        roots
            .iter()
            .flat_map(|root| {
                let itself = root.file_name().is_some_and(|n| n == package);
                std::iter::once(root.join(package).join(relative))
                    .chain(itself.then(|| root.join(relative)))
            })
            .collect()
    } else {
        vec![match filename.strip_prefix("file://") {
            Some(abs) => PathBuf::from(abs),
            None => urdf_dir.join(filename),
        }]
    };
    let mut looked = Vec::new();
    for candidate in candidates {
        match crate::input::not_a_regular_file(&candidate) {
            None => return Ok(candidate),
            Some(why) => looked.push(format!("{} ({why})", candidate.display())),
        }
    }
    let more = looked.len().saturating_sub(10);
    looked.truncate(10);
    if more > 0 {
        looked.push(format!("and {more} more"));
    }
    Err(format!("looked for it at {}", looked.join(", ")))
}

/// Mesh formats read for collision geometry (by file extension, case-insensitive).
pub const MESH_FORMATS: &str = "STL (.stl), Wavefront OBJ (.obj) or COLLADA (.dae)";

/// Largest distance (m) from a mesh's exact convex hull to the simplified hull that
/// collision checks use: 0.5 mm, a twentieth of the default `physics.object_clearance`.
pub const HULL_TOLERANCE: f64 = 5e-4;

/// Most vertices a simplified hull keeps. A convex shape's support point is a scan over
/// its vertices, and a propagation step asks for many: a link hull of a few hundred
/// vertices would cost more than the rest of the step.
pub const MAX_HULL_VERTICES: usize = 64;

/// Most triangles a collision mesh may have. Only its convex hull collides, and the
/// hull's time grows with the vertices, faster than in proportion: a sphere of 50 000
/// triangles (every vertex on the hull, the worst case) loads in 0.4 s, of 100 000 in
/// 0.9 s, of 200 000 in 2.6 s (docs/notes/mesh-robots.md); a visual mesh of a million
/// took half a minute and 800 MB before planning started. A collision mesh needs
/// hundreds to thousands.
pub const MAX_MESH_TRIANGLES: usize = 100_000;

/// Refuses a mesh of more than [`MAX_MESH_TRIANGLES`], naming both numbers.
fn check_triangles(triangles: u64) -> std::result::Result<(), String> {
    match triangles <= MAX_MESH_TRIANGLES as u64 {
        true => Ok(()),
        false => Err(format!(
            "{triangles} triangles; a collision mesh may have at most {MAX_MESH_TRIANGLES} \
             (only its convex hull collides: decimate it, or give the collision element a \
             simpler mesh than the visual one)"
        )),
    }
}

/// Refuses a binary STL whose size is not what its header says: 84 bytes, then 50 per
/// triangle of the count in bytes 80-83 (a header claiming 2^31 triangles over a few
/// would otherwise load silently, or be read as far as the file goes). A file that
/// starts with `solid` and is all ASCII is an ASCII STL, which has no count.
fn check_stl_size(bytes: &[u8]) -> std::result::Result<(), String> {
    let ascii = bytes.trim_ascii_start().starts_with(b"solid") && bytes.is_ascii();
    if ascii {
        return Ok(());
    }
    let Some(count) = bytes.get(80..84) else {
        return Err(format!(
            "{} bytes: too short for a binary STL (84 bytes of header and count)",
            bytes.len()
        ));
    };
    let triangles = u32::from_le_bytes([count[0], count[1], count[2], count[3]]);
    let expected = 84 + 50 * u64::from(triangles);
    match expected == bytes.len() as u64 {
        // Counted before the file is parsed: a huge mesh costs nothing to refuse.
        true => check_triangles(triangles.into()),
        false => Err(format!(
            "binary STL header says {triangles} triangles ({expected} bytes), the file has {} bytes",
            bytes.len()
        )),
    }
}

/// A mesh that encloses at least this share of its convex hull's volume collides as its
/// hull; one that encloses less is decomposed ([`load_collision_mesh`]). A tessellated
/// cylinder or box encloses all of it; Baxter's torso half (0.069 of 0.135 m^3), its
/// pedestal a quarter.
pub const CONVEX_ENOUGH: f64 = 0.8;

/// Most edges (as a share) a mesh may leave open, bordering one triangle, for its enclosed
/// volume to count. Baxter's torso leaves 7.5 % open (1 067 of 14 272: small gaps between
/// its parts) and encloses half its hull; a mesh of loose faces is far above.
pub const MAX_OPEN_EDGES: f64 = 0.1;

/// The convex parts V-HACD is asked for (each a shape every collision query of its link
/// visits). Its binary splits go as deep as this number needs and one level more, and
/// parry's V-HACD does not merge them back: a mesh may become up to twice as many (a
/// Baxter elbow's visual mesh, 13 124 triangles: 25). Baxter's torso becomes 11, its
/// pedestal 9.
pub const CONVEX_PARTS: u32 = 16;

/// V-HACD's voxel grid (cells along the mesh's longest side). 32 cells decompose Baxter's
/// torso (9 159 triangles) into 11 parts enclosing 0.085 m^3 of the mesh's 0.069 in
/// 0.13 s; 64 cells into 13 parts and 0.076 m^3 in 0.38 s, for every scene load.
pub const DECOMPOSITION_RESOLUTION: u32 = 32;

/// Reads a mesh (STL, OBJ or COLLADA), scales it (per axis, in the mesh's own frame) and
/// returns the convex hull of all its vertices, simplified to within [`HULL_TOLERANCE`]
/// (see [`simplify_hull`]). COLLADA's `<unit>`, `<up_axis>` and node transforms are
/// applied; OBJ material files are not read.
pub fn load_convex_mesh(path: &Path, scale: [f64; 3]) -> Result<Primitive> {
    let mesh = read_mesh(path, scale)?;
    convex_hull(path, &mesh.points)
}

/// Reads a link's collision mesh as [`load_convex_mesh`] does and returns the convex
/// shapes it collides as: its hull when the mesh is open or encloses at least
/// [`CONVEX_ENOUGH`] of the hull's volume, else the exact hulls of a V-HACD decomposition
/// (about [`CONVEX_PARTS`], each the hull of the mesh's own triangles clipped to a part,
/// so no part reaches past the mesh's hull), each simplified to within
/// [`HULL_TOLERANCE`].
///
/// A process keeps what it decomposed, by the file's bytes, format and scale: `plan` loads
/// its scene more than once (Baxter's torso costs 0.2 s each time).
pub fn load_collision_mesh(path: &Path, scale: [f64; 3]) -> Result<Vec<Primitive>> {
    static DECOMPOSED: Mutex<Vec<Decomposed>> = Mutex::new(Vec::new());
    let bytes = read_mesh_bytes(path)?;
    // The format is read from the extension: the same bytes may be another mesh.
    let mut hasher = DefaultHasher::new();
    bytes.hash(&mut hasher);
    path.extension()
        .map(|e| e.to_ascii_lowercase())
        .hash(&mut hasher);
    let key = (hasher.finish(), scale.map(f64::to_bits));
    let known = |cache: &[Decomposed]| {
        cache
            .iter()
            .find(|(hash, scale, _)| (*hash, *scale) == key)
            .map(|(_, _, parts)| parts.clone())
    };
    // A poisoned lock only means another thread panicked while holding it: the list is
    // whole (each entry is pushed complete), so it stays usable.
    let lock = || {
        DECOMPOSED
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    };
    if let Some(parts) = known(&lock()) {
        return Ok(parts);
    }
    let mesh = parse_mesh(path, &bytes, scale)?;
    let parts = mesh
        .concave_volume_share()
        .filter(|share| *share < CONVEX_ENOUGH)
        .map(|_| mesh.convex_parts())
        .unwrap_or_default();
    // The single hull only where no parts replace it (a flat mesh is refused here).
    let parts = match parts.is_empty() {
        true => vec![convex_hull(path, &mesh.points)?],
        false => parts,
    };
    lock().push((key.0, key.1, parts.clone()));
    Ok(parts)
}

/// A decomposed mesh a process keeps: its bytes' and format's hash, its scale's bits and
/// its parts.
type Decomposed = (u64, [u64; 3], Vec<Primitive>);

/// A mesh's vertices (scaled, z up) and triangles, as its file lists them.
struct TriangleMesh {
    points: Vec<Point3<f64>>,
    triangles: Vec<[u32; 3]>,
}

impl TriangleMesh {
    /// The volume the mesh encloses as a share of its convex hull's, when it is closed
    /// but for small holes (at most [`MAX_OPEN_EDGES`] of its edges border one triangle,
    /// vertices joined where they coincide: a hole changes the divergence sum by the
    /// cone over it); `None` for a mostly open surface, whose enclosed volume means
    /// nothing.
    fn concave_volume_share(&self) -> Option<f64> {
        // STL and COLLADA list a vertex once per triangle around it: join equal ones.
        let mut index_of = HashMap::new();
        let welded: Vec<u32> = self
            .points
            .iter()
            .map(|p| {
                let next = index_of.len() as u32;
                *index_of.entry(p.coords.map(f64::to_bits)).or_insert(next)
            })
            .collect();
        let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| welded[i as usize]);
            for (u, v) in [(a, b), (b, c), (c, a)] {
                *edges.entry((u.min(v), u.max(v))).or_default() += 1;
            }
        }
        let open = edges.values().filter(|&&n| n != 2).count();
        if edges.is_empty() || open as f64 > MAX_OPEN_EDGES * edges.len() as f64 {
            return None;
        }
        let (hull_points, hull_triangles) =
            parry3d_f64::transformation::try_convex_hull(&self.points).ok()?;
        let hull = enclosed_volume(&hull_points, &hull_triangles);
        (hull > 0.0).then(|| enclosed_volume(&self.points, &self.triangles) / hull)
    }

    /// The simplified exact hulls of a V-HACD decomposition (flat parts left out; empty if
    /// none is solid or the decomposition fails).
    fn convex_parts(&self) -> Vec<Primitive> {
        let parameters = VHACDParameters {
            resolution: DECOMPOSITION_RESOLUTION,
            max_convex_hulls: CONVEX_PARTS,
            ..VHACDParameters::default()
        };
        // parry's decomposition asserts on inputs it cannot voxelize: a mesh that trips
        // one collides as its hull instead (caught as the COLLADA reader's panics are).
        let hulls = std::panic::catch_unwind(|| {
            VHACD::decompose(&parameters, &self.points, &self.triangles, true)
                .compute_exact_convex_hulls(&self.points, &self.triangles)
        })
        .unwrap_or_default();
        hulls
            .iter()
            .filter_map(|(points, _)| simplify_hull(points, HULL_TOLERANCE, MAX_HULL_VERTICES))
            .map(|simplified| Primitive::ConvexHull {
                points: simplified.points,
            })
            .collect()
    }
}

/// The volume a closed triangle mesh encloses (m^3): the divergence theorem's sum of the
/// tetrahedra from the origin to each triangle, whichever way the triangles turn.
fn enclosed_volume(points: &[Point3<f64>], triangles: &[[u32; 3]]) -> f64 {
    let signed: f64 = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| points[i as usize].coords);
            a.dot(&b.cross(&c)) / 6.0
        })
        .sum();
    signed.abs()
}

/// The simplified convex hull of a mesh's points, as the one collision shape of `path`.
fn convex_hull(path: &Path, points: &[Point3<f64>]) -> Result<Primitive> {
    let simplified =
        simplify_hull(points, HULL_TOLERANCE, MAX_HULL_VERTICES).ok_or_else(|| Error::Mesh {
            file: path.to_path_buf(),
            message: "the mesh is flat (no convex hull)".into(),
        })?;
    Ok(Primitive::ConvexHull {
        points: simplified.points,
    })
}

/// Reads a mesh file's vertices and triangles (see [`load_convex_mesh`]).
fn read_mesh(path: &Path, scale: [f64; 3]) -> Result<TriangleMesh> {
    parse_mesh(path, &read_mesh_bytes(path)?, scale)
}

/// A mesh file's bytes (a regular file within the mesh size limit).
fn read_mesh_bytes(path: &Path) -> Result<Vec<u8>> {
    crate::input::read_bytes(path, crate::input::MAX_MESH_BYTES)
        .map_err(|message| Error::io(path, message))
}

/// The vertices and triangles of mesh file `path`'s `bytes` (see [`load_convex_mesh`]).
fn parse_mesh(path: &Path, bytes: &[u8], scale: [f64; 3]) -> Result<TriangleMesh> {
    let mesh_error = |message: String| Error::Mesh {
        file: path.to_path_buf(),
        message,
    };
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let scene = match extension.as_deref() {
        Some("stl") => {
            check_stl_size(bytes).map_err(mesh_error)?;
            mesh_loader::stl::from_slice(bytes)
        }
        Some("obj") => mesh_loader::obj::from_slice(bytes, Some(path), |_: &Path| {
            // Materials do not collide: the `.mtl` file is neither needed nor read.
            Err::<Vec<u8>, _>(std::io::Error::other("not read"))
        }),
        // mesh-loader 0.1.13 indexes a COLLADA file's arrays as its indices say: a file
        // whose indices point past its arrays panicked (found by tests/integration/fuzz.rs).
        // The panic is caught and the file refused like any malformed one.
        Some("dae") => std::panic::catch_unwind(|| mesh_loader::collada::from_slice(bytes))
            .unwrap_or_else(|_| {
                Err(std::io::Error::other(
                    "COLLADA indices beyond the arrays they index",
                ))
            }),
        _ => return Err(mesh_error(format!("the mesh must be {MESH_FORMATS}"))),
    }
    .map_err(|e| mesh_error(e.to_string()))?;
    check_triangles(scene.meshes.iter().map(|m| m.faces.len() as u64).sum()).map_err(mesh_error)?;
    let up = match extension.as_deref() {
        Some("dae") => collada_up_axis(bytes),
        _ => UpAxis::Z,
    };
    let mut points = Vec::new();
    let mut triangles = Vec::new();
    for mesh in &scene.meshes {
        let first = points.len() as u32;
        points.extend(mesh.vertices.iter().map(|v| {
            let [x, y, z] = up.to_z_up(v.map(f64::from));
            Point3::new(x * scale[0], y * scale[1], z * scale[2])
        }));
        triangles.extend(mesh.faces.iter().map(|f| f.map(|i| first + i)));
    }
    if points.len() < 4
        || points
            .iter()
            .any(|p| !p.coords.iter().all(|c| c.is_finite()))
    {
        return Err(mesh_error(
            "needs at least 4 finite vertices to make a solid".into(),
        ));
    }
    // A face naming a vertex the file does not have leaves the mesh open, not a crash.
    triangles.retain(|t| t.iter().all(|&i| (i as usize) < points.len()));
    Ok(TriangleMesh { points, triangles })
}

/// The axis a COLLADA file calls up (`<asset><up_axis>`, Y by default in the standard);
/// URDF's frames have z up.
#[derive(Clone, Copy, Debug, PartialEq)]
enum UpAxis {
    X,
    Y,
    Z,
}

impl UpAxis {
    /// The point in a z-up frame. COLLADA fixes each up axis's right and in axes (X_UP:
    /// right -y, in +z; Y_UP: right +x, in +z; Z_UP: right +x, in -y), so Y up turns
    /// (x, y, z) into (x, -z, y) and X up into (-y, -z, x).
    fn to_z_up(self, [x, y, z]: [f64; 3]) -> [f64; 3] {
        match self {
            UpAxis::X => [-y, -z, x],
            UpAxis::Y => [x, -z, y],
            UpAxis::Z => [x, y, z],
        }
    }
}

/// The `<up_axis>` of a COLLADA document (mesh-loader applies `<unit>` and node
/// transforms, not the up axis). Y_UP when absent, as the standard says.
fn collada_up_axis(bytes: &[u8]) -> UpAxis {
    let text = String::from_utf8_lossy(bytes);
    let value = text
        .split_once("<up_axis>")
        .and_then(|(_, rest)| rest.split_once("</up_axis>"))
        .map(|(value, _)| value.trim());
    match value {
        Some("X_UP") => UpAxis::X,
        Some("Z_UP") => UpAxis::Z,
        _ => UpAxis::Y,
    }
}

/// A convex hull reduced to a few of its vertices.
#[derive(Clone, Debug)]
pub struct SimplifiedHull {
    /// The kept vertices (a subset of the exact hull's, so the simplified hull lies inside
    /// the exact one).
    pub points: Vec<Point3<f64>>,
    /// How many vertices the exact hull has.
    pub exact_vertices: usize,
    /// The Hausdorff distance between the exact and the simplified hull (m): the largest
    /// distance from an exact hull vertex to the simplified hull.
    pub error: f64,
}

/// Simplifies the convex hull of `points` greedily: starting from a tetrahedron of
/// extreme vertices, the exact hull's vertex furthest outside the kept ones' hull is
/// added until none is further than `tolerance` (m) or `max_vertices` are kept. The
/// result lies inside the exact hull; its `error` is measured over every exact vertex.
/// `None` for flat or empty input.
pub fn simplify_hull(
    points: &[Point3<f64>],
    tolerance: f64,
    max_vertices: usize,
) -> Option<SimplifiedHull> {
    // A mesh lists each vertex once per triangle around it (an STL six times): the hull's
    // time grows faster than its input, so each point goes in once, in the order first met.
    let mut seen = HashSet::new();
    let unique: Vec<Point3<f64>> = points
        .iter()
        .filter(|p| seen.insert(p.coords.map(f64::to_bits)))
        .copied()
        .collect();
    let (exact, _) = parry3d_f64::transformation::try_convex_hull(&unique).ok()?;
    if exact.len() < 4 {
        return None;
    }
    let mut kept = initial_tetrahedron(&exact)?;
    // Lazily: a vertex's distance from the kept hull only shrinks as the hull grows, so a
    // distance measured earlier bounds it from above. Each round measures again only the
    // vertices whose bound could still make them the furthest, in order of their bounds;
    // the choice is the exact one (the furthest, the lowest index among equals), but a
    // mesh of 50 000 triangles no longer costs its 25 000 hull vertices' distances in
    // each of 60 rounds (10 s).
    let mut bounds: BinaryHeap<Bound> = (0..exact.len())
        .map(|index| Bound {
            distance: f64::INFINITY,
            index,
        })
        .collect();
    loop {
        let hull = ConvexPolyhedron::from_convex_hull(
            &kept.iter().map(|&i| exact[i]).collect::<Vec<_>>(),
        )?;
        let mut measured = Vec::new();
        let mut furthest: Option<Bound> = None;
        while let Some(top) = bounds.peek() {
            if furthest.is_some_and(|f| top.distance < f.distance - BOUND_SLACK) {
                break;
            }
            let index = bounds.pop().expect("peeked").index;
            let distance = hull.distance_to_local_point(&exact[index], true);
            // Within the tolerance now, within it for good: the hull only grows.
            if distance > tolerance {
                let bound = Bound { distance, index };
                if furthest.is_none_or(|f| bound > f) {
                    furthest = Some(bound);
                }
                measured.push(bound);
            }
        }
        let error = furthest.map_or(0.0, |f| f.distance);
        if error <= tolerance || kept.len() >= max_vertices.max(4) {
            let error = exact
                .iter()
                .map(|p| hull.distance_to_local_point(p, true))
                .fold(0.0, f64::max);
            return Some(SimplifiedHull {
                points: kept.iter().map(|&i| exact[i]).collect(),
                exact_vertices: exact.len(),
                error,
            });
        }
        let worst = furthest.expect("beyond the tolerance").index;
        kept.push(worst);
        bounds.extend(measured.into_iter().filter(|b| b.index != worst));
    }
}

/// How far a measured distance may rise as the hull grows (m): in exact arithmetic it
/// only shrinks, but GJK's rounding moves it by about 1e-16 m. Every vertex whose bound
/// is within this of the furthest is measured again, so that the choice is the one
/// measuring every vertex makes (a symmetric mesh has many as far).
const BOUND_SLACK: f64 = 1e-9;

/// An exact hull vertex's distance from the kept hull, or a bound on it from above; the
/// greater is the one further out, and of two as far the one of the lower index (the
/// vertex the greedy choice takes first).
#[derive(Clone, Copy, Debug)]
struct Bound {
    distance: f64,
    index: usize,
}

impl PartialEq for Bound {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Bound {}

impl PartialOrd for Bound {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Bound {
    fn cmp(&self, other: &Self) -> Ordering {
        self.distance
            .total_cmp(&other.distance)
            .then(other.index.cmp(&self.index))
    }
}

/// Four vertices spanning a solid: the extremes along x (or whichever axis is longest),
/// the one furthest from their line, the one furthest from their plane.
fn initial_tetrahedron(points: &[Point3<f64>]) -> Option<Vec<usize>> {
    let furthest = |score: &dyn Fn(&Point3<f64>) -> f64| {
        (0..points.len()).max_by(|&a, &b| score(&points[a]).total_cmp(&score(&points[b])))
    };
    let axis = (0..3).max_by(|&a, &b| {
        let extent = |k: usize| {
            let (lo, hi) = points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p[k]), hi.max(p[k]))
                });
            hi - lo
        };
        extent(a).total_cmp(&extent(b))
    })?;
    let a = furthest(&|p| -p[axis])?;
    let b = furthest(&|p| p[axis])?;
    let ab = (points[b] - points[a]).try_normalize(1e-12)?;
    let c = furthest(&|p| (p - points[a]).cross(&ab).norm())?;
    let normal = ab.cross(&(points[c] - points[a])).try_normalize(1e-12)?;
    let d = furthest(&|p| (p - points[a]).dot(&normal).abs())?;
    ((points[d] - points[a]).dot(&normal).abs() > 1e-9).then(|| vec![a, b, c, d])
}
