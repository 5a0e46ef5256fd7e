//! The part of a convex solid between two heights: the solid cut by a horizontal slab
//! `z_min <= z <= z_max` (world frame, m), given as points whose convex hull it is.
//!
//! Polytopes (boxes, hulls, and cylinders as 32-sided prisms) are cut exactly: the cut's
//! corners are the solid's vertices inside the slab and its edges' crossings of the slab's
//! two planes. Round ends (spheres, capsules) are cut as circles: a sphere meets the slab
//! in a body whose outline from above is a disc of radius `sqrt(r^2 - d^2)`, with `d` the
//! centre's distance from the slab, so a sphere gives that disc at the slab height nearest
//! its centre, and a capsule the discs of spheres sampled along its segment.

use super::Geometry;
use nalgebra::{Isometry3, Point3};
use parry3d_f64::shape::TypedShape;

/// Points around a cut circle, and around a cylinder's rims.
const CIRCLE_POINTS: usize = 32;
/// Spheres sampled along a capsule's segment.
const CAPSULE_SAMPLES: usize = 9;

/// Appends to `out` the points (world frame) whose convex hull is the part of `geometry`,
/// on a body at `body`, between `z_min` and `z_max`; nothing if the solid misses the slab.
pub fn slab_section(
    geometry: &Geometry,
    body: &Isometry3<f64>,
    z_min: f64,
    z_max: f64,
    out: &mut Vec<Point3<f64>>,
) {
    let pose = geometry.world_pose(body);
    let slab = Slab { z_min, z_max };
    match geometry.shape.as_typed_shape() {
        TypedShape::Ball(b) => slab.cut_sphere(&(pose * Point3::origin()), b.radius, out),
        TypedShape::Capsule(c) => {
            let (a, b) = (pose * c.segment.a, pose * c.segment.b);
            for k in 0..CAPSULE_SAMPLES {
                let t = k as f64 / (CAPSULE_SAMPLES - 1) as f64;
                slab.cut_sphere(&(a + t * (b - a)), c.radius, out);
            }
        }
        TypedShape::Cuboid(c) => {
            let h = c.half_extents;
            let corner =
                |i: usize| pose * Point3::new(sign(i, 0) * h.x, sign(i, 1) * h.y, sign(i, 2) * h.z);
            let corners: Vec<Point3<f64>> = (0..8).map(corner).collect();
            // Edges join corners that differ in one coordinate's sign.
            let edges = (0..8).flat_map(|i| {
                (0..3)
                    .map(move |bit| (i, i | 1 << bit))
                    .filter(move |&(a, b)| a != b)
            });
            slab.cut_polytope(&corners, edges, out);
        }
        TypedShape::Cylinder(c) => {
            // parry's cylinder runs along its local y: two rims joined by straight sides.
            let n = CIRCLE_POINTS;
            let rims: Vec<Point3<f64>> = [-c.half_height, c.half_height]
                .iter()
                .flat_map(|&y| {
                    (0..n).map(move |k| {
                        let a = k as f64 * std::f64::consts::TAU / n as f64;
                        pose * Point3::new(c.radius * a.cos(), y, c.radius * a.sin())
                    })
                })
                .collect();
            let edges =
                (0..n).flat_map(|k| [(k, (k + 1) % n), (n + k, n + (k + 1) % n), (k, n + k)]);
            slab.cut_polytope(&rims, edges, out);
        }
        TypedShape::ConvexPolyhedron(p) => {
            let vertices: Vec<Point3<f64>> = p.points().iter().map(|q| pose * q).collect();
            let edges = p
                .edges()
                .iter()
                .map(|e| (e.vertices.x as usize, e.vertices.y as usize));
            slab.cut_polytope(&vertices, edges, out);
        }
        _ => {
            // Other shapes are not built by `Geometry::new`; their world box stands in.
            let aabb = geometry.aabb(body);
            let corners: Vec<Point3<f64>> = aabb.vertices().to_vec();
            let edges = (0..8).flat_map(|i| (i + 1..8).map(move |j| (i, j)));
            slab.cut_polytope(&corners, edges, out);
        }
    }
}

/// -1 or +1: bit `bit` of corner index `i`.
fn sign(i: usize, bit: usize) -> f64 {
    if i >> bit & 1 == 1 {
        1.0
    } else {
        -1.0
    }
}

struct Slab {
    z_min: f64,
    z_max: f64,
}

impl Slab {
    fn contains(&self, p: &Point3<f64>) -> bool {
        p.z >= self.z_min && p.z <= self.z_max
    }

    /// The cut of a convex polytope of `vertices` whose edges (vertex index pairs) are
    /// `edges`: vertices inside, and edges' crossings of the two planes.
    fn cut_polytope(
        &self,
        vertices: &[Point3<f64>],
        edges: impl Iterator<Item = (usize, usize)>,
        out: &mut Vec<Point3<f64>>,
    ) {
        out.extend(vertices.iter().filter(|p| self.contains(p)));
        for (a, b) in edges {
            let (p, q) = (&vertices[a], &vertices[b]);
            for z in [self.z_min, self.z_max] {
                if (p.z - z) * (q.z - z) < 0.0 {
                    out.push(p + (z - p.z) / (q.z - p.z) * (q - p));
                }
            }
        }
    }

    /// The cut of a sphere, seen from above: the circle of the widest part of it within
    /// the slab, at the height of the slab nearest the centre.
    fn cut_sphere(&self, centre: &Point3<f64>, radius: f64, out: &mut Vec<Point3<f64>>) {
        let z = centre.z.clamp(self.z_min, self.z_max);
        let squared = radius * radius - (centre.z - z).powi(2);
        if squared <= 0.0 {
            return;
        }
        let r = squared.sqrt();
        out.extend((0..CIRCLE_POINTS).map(|k| {
            let a = k as f64 * std::f64::consts::TAU / CIRCLE_POINTS as f64;
            Point3::new(centre.x + r * a.cos(), centre.y + r * a.sin(), z)
        }));
    }
}
