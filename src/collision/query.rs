//! Pairwise queries between placed shapes.

use super::geometry::Geometry;
use nalgebra::{Isometry3, Point3, Unit, Vector3};
use parry3d_f64::query::{
    self, ContactManifold, DefaultQueryDispatcher, PersistentQueryDispatcher,
};

/// Do the shapes overlap (touching counts)?
pub fn intersects(
    a: &Geometry,
    pose_a: &Isometry3<f64>,
    b: &Geometry,
    pose_b: &Isometry3<f64>,
) -> bool {
    query::intersection_test(
        &a.world_pose(pose_a),
        a.shape.as_ref(),
        &b.world_pose(pose_b),
        b.shape.as_ref(),
    )
    .unwrap_or(true)
}

/// Signed distance between the shapes (m): positive when apart, minus the penetration
/// depth when overlapping. `None` when they are farther apart than `max_distance`.
pub fn signed_distance(
    a: &Geometry,
    pose_a: &Isometry3<f64>,
    b: &Geometry,
    pose_b: &Isometry3<f64>,
    max_distance: f64,
) -> Option<f64> {
    query::contact(
        &a.world_pose(pose_a),
        a.shape.as_ref(),
        &b.world_pose(pose_b),
        b.shape.as_ref(),
        max_distance,
    )
    .ok()
    .flatten()
    .map(|c| c.dist)
}

/// One point of a contact manifold between shapes `a` and `b`, world frame.
#[derive(Clone, Copy, Debug)]
pub struct ContactPoint {
    /// Point on the surface of `a` (m).
    pub point_a: Point3<f64>,
    /// Point on the surface of `b` (m).
    pub point_b: Point3<f64>,
    /// Unit normal pointing out of `a`, towards `b`.
    pub normal_a: Unit<Vector3<f64>>,
    /// Signed distance (m): negative when penetrating.
    pub distance: f64,
}

/// All contact points between `a` and `b` closer than `prediction` (m), appended to `out`.
///
/// Face-to-face contacts come back as several points (the corners of the touching patch),
/// which is what lets a flat pusher push a box straight. A fresh manifold is used every
/// call so the answer depends on the poses only (no history), keeping propagation
/// deterministic.
pub fn contact_points(
    a: &Geometry,
    pose_a: &Isometry3<f64>,
    b: &Geometry,
    pose_b: &Isometry3<f64>,
    prediction: f64,
    out: &mut Vec<ContactPoint>,
) {
    let world_a = a.world_pose(pose_a);
    let world_b = b.world_pose(pose_b);
    let pos12 = world_a.inv_mul(&world_b);
    let mut manifold: ContactManifold<(), ()> = ContactManifold::new();
    let supported = DefaultQueryDispatcher
        .contact_manifold_convex_convex(
            &pos12,
            a.shape.as_ref(),
            b.shape.as_ref(),
            None,
            None,
            prediction,
            &mut manifold,
        )
        .is_ok();
    if supported && !manifold.points.is_empty() {
        let normal_a = Unit::new_normalize(world_a.rotation * manifold.local_n1);
        for p in &manifold.points {
            if p.dist <= prediction {
                out.push(ContactPoint {
                    point_a: world_a * p.local_p1,
                    point_b: world_b * p.local_p2,
                    normal_a,
                    distance: p.dist,
                });
            }
        }
        return;
    }
    // Pairs without a manifold generator fall back to the single closest-point contact.
    if let Ok(Some(c)) = query::contact(
        &world_a,
        a.shape.as_ref(),
        &world_b,
        b.shape.as_ref(),
        prediction,
    ) {
        out.push(ContactPoint {
            point_a: c.point1,
            point_b: c.point2,
            normal_a: c.normal1,
            distance: c.dist,
        });
    }
}
