//! Top-down outlines: what a convex solid covers when seen from above, as a polygon in
//! world x, y (m).

use crate::collision::Geometry;
use crate::physics::Footprint;
use crate::Pose2;
use nalgebra::{Isometry3, Point3, Vector2};
use parry3d_f64::shape::TypedShape;

/// Points sampled on the solid's surface that bound it from above (exactly for boxes and
/// hulls, to 24 points per circle for round shapes).
fn surface_points(geometry: &Geometry, body: &Isometry3<f64>) -> Vec<Vector2<f64>> {
    let pose = geometry.world_pose(body);
    let circle = |centre: Point3<f64>, radius: f64, out: &mut Vec<Vector2<f64>>| {
        // A sphere of `radius` seen from above: a disc.
        let c = pose * centre;
        out.extend((0..24).map(|k| {
            let a = k as f64 * std::f64::consts::TAU / 24.0;
            Vector2::new(c.x + radius * a.cos(), c.y + radius * a.sin())
        }));
    };
    let mut out = Vec::new();
    match geometry.shape.as_typed_shape() {
        TypedShape::Cuboid(c) => {
            let h = c.half_extents;
            for sx in [-1.0, 1.0] {
                for sy in [-1.0, 1.0] {
                    for sz in [-1.0, 1.0] {
                        out.push(
                            (pose * Point3::new(sx * h.x, sy * h.y, sz * h.z))
                                .xy()
                                .coords,
                        );
                    }
                }
            }
        }
        TypedShape::Ball(b) => circle(Point3::origin(), b.radius, &mut out),
        TypedShape::Capsule(c) => {
            circle(c.segment.a, c.radius, &mut out);
            circle(c.segment.b, c.radius, &mut out);
        }
        TypedShape::Cylinder(c) => {
            // parry's cylinder runs along its local y: two rims.
            for y in [-c.half_height, c.half_height] {
                out.extend((0..24).map(|k| {
                    let a = k as f64 * std::f64::consts::TAU / 24.0;
                    (pose * Point3::new(c.radius * a.cos(), y, c.radius * a.sin()))
                        .xy()
                        .coords
                }));
            }
        }
        TypedShape::ConvexPolyhedron(p) => {
            out.extend(p.points().iter().map(|q| (pose * q).xy().coords))
        }
        _ => {
            let aabb = geometry.aabb(body);
            out.extend([
                Vector2::new(aabb.mins.x, aabb.mins.y),
                Vector2::new(aabb.maxs.x, aabb.mins.y),
                Vector2::new(aabb.maxs.x, aabb.maxs.y),
                Vector2::new(aabb.mins.x, aabb.maxs.y),
            ]);
        }
    }
    out
}

/// The top-down outline of a convex solid on a body at `body`.
pub fn shape_outline(geometry: &Geometry, body: &Isometry3<f64>) -> Vec<Vector2<f64>> {
    convex_hull(surface_points(geometry, body))
}

/// An object's footprint at a pose, as a polygon (circles to 32 points).
pub fn footprint_outline(footprint: &Footprint, pose: &Pose2) -> Vec<Vector2<f64>> {
    let local: Vec<Vector2<f64>> = match footprint {
        Footprint::Circle { radius } => (0..32)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 32.0;
                Vector2::new(radius * a.cos(), radius * a.sin())
            })
            .collect(),
        Footprint::Polygon { vertices } => vertices.clone(),
    };
    local
        .iter()
        .map(|v| pose.translation() + pose.rotation() * v)
        .collect()
}

/// Counter-clockwise convex hull (Andrew's monotone chain).
pub fn convex_hull(mut points: Vec<Vector2<f64>>) -> Vec<Vector2<f64>> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    points.dedup_by(|a, b| (*a - *b).norm() < 1e-12);
    if points.len() < 3 {
        return points;
    }
    let cross = |o: &Vector2<f64>, a: &Vector2<f64>, b: &Vector2<f64>| (a - o).perp(&(b - o));
    let mut hull: Vec<Vector2<f64>> = Vec::with_capacity(2 * points.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Vector2<f64>>> = if pass == 0 {
            Box::new(points.iter())
        } else {
            Box::new(points.iter().rev())
        };
        for p in iter {
            while hull.len() >= start + 2
                && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(*p);
        }
        hull.pop();
    }
    hull
}
