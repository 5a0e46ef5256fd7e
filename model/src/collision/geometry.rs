//! Building collision shapes from primitive descriptions.
//!
//! Frames: every primitive is centred on its body-local pose; cylinders and capsules run
//! along their local **z** axis, as in URDF (parry's own cylinders run along y, so they are
//! turned by Rx(pi/2) here, once).

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::shape::SharedShape;
use std::f64::consts::FRAC_PI_2;

/// Smallest volume of a convex hull (m^3, a 0.1 mm cube): thinner hulls are flat.
const MIN_HULL_VOLUME: f64 = 1e-12;

/// A primitive solid, dimensions in metres.
#[derive(Clone, Debug, PartialEq)]
pub enum Primitive {
    /// Box with full side lengths along x, y, z.
    Box {
        /// Full side lengths along x, y, z (m).
        size: Vector3<f64>,
    },
    /// Cylinder along z, `length` is the full height.
    Cylinder {
        /// Radius (m).
        radius: f64,
        /// Full height along z (m).
        length: f64,
    },
    /// Ball centred on the frame's origin.
    Sphere {
        /// Radius (m).
        radius: f64,
    },
    /// Capsule along z; `length` is the length of the inner segment (URDF convention).
    Capsule {
        /// Radius of the cylinder and of the end caps (m).
        radius: f64,
        /// Length of the inner segment along z (m).
        length: f64,
    },
    /// Convex hull of the points (e.g. a mesh's vertices).
    ConvexHull {
        /// The points, in the shape's frame (m).
        points: Vec<Point3<f64>>,
    },
}

/// Hulls with more vertices than this get their world bounding box from their local one
/// (turned, so a little larger) rather than from every vertex: the broad phase asks for
/// every link's box at every step.
const EXACT_AABB_MAX_VERTICES: usize = 16;

/// A shape attached to a body: `local` places the shape in the body frame.
#[derive(Clone)]
pub struct Geometry {
    /// `X_BS`: the shape's frame in the body frame.
    pub local: Isometry3<f64>,
    /// The shape, in its own frame (parry).
    pub shape: SharedShape,
    /// For a hull of many vertices: its bounding box in the shape's frame.
    local_aabb: Option<Aabb>,
}

impl std::fmt::Debug for Geometry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Geometry")
            .field("local", &self.local)
            .field("shape", &self.shape.shape_type())
            .finish()
    }
}

impl Geometry {
    /// Builds the shape of `primitive` placed at `local` in the body frame.
    /// Returns `None` for degenerate input (a hull of coplanar points, say).
    pub fn new(primitive: &Primitive, local: Isometry3<f64>) -> Option<Geometry> {
        let z_to_y = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), FRAC_PI_2);
        let (shape, local) = match primitive {
            Primitive::Box { size } => (
                SharedShape::cuboid(size.x / 2.0, size.y / 2.0, size.z / 2.0),
                local,
            ),
            Primitive::Cylinder { radius, length } => {
                (SharedShape::cylinder(length / 2.0, *radius), local * z_to_y)
            }
            Primitive::Sphere { radius } => (SharedShape::ball(*radius), local),
            Primitive::Capsule { radius, length } => {
                (SharedShape::capsule_z(length / 2.0, *radius), local)
            }
            Primitive::ConvexHull { points } => {
                let hull = SharedShape::convex_hull(points)?;
                // parry builds a hull of coplanar points too; it has no volume to collide
                // with (m^3: a hull thinner than a 0.1 mm cube's volume is flat).
                if hull.mass_properties(1.0).mass() <= MIN_HULL_VOLUME {
                    return None;
                }
                (hull, local)
            }
        };
        let local_aabb = shape
            .as_convex_polyhedron()
            .filter(|hull| hull.points().len() > EXACT_AABB_MAX_VERTICES)
            .map(|hull| hull.local_aabb());
        Some(Geometry {
            local,
            shape,
            local_aabb,
        })
    }

    /// World pose of the shape when its body is at `body_pose`.
    #[inline]
    pub fn world_pose(&self, body_pose: &Isometry3<f64>) -> Isometry3<f64> {
        body_pose * self.local
    }

    /// World bounding box when the body is at `body_pose` (for hulls of many vertices, the
    /// box around their turned local box).
    #[inline]
    pub fn aabb(&self, body_pose: &Isometry3<f64>) -> Aabb {
        match &self.local_aabb {
            Some(local) => local.transform_by(&self.world_pose(body_pose)),
            None => self.shape.compute_aabb(&self.world_pose(body_pose)),
        }
    }
}

/// Bounding box of several shapes of one body, or `None` when it has none.
pub fn union_aabb(geometry: &[Geometry], body_pose: &Isometry3<f64>) -> Option<Aabb> {
    use parry3d_f64::bounding_volume::BoundingVolume;
    geometry
        .iter()
        .map(|g| g.aabb(body_pose))
        .reduce(|a, b| a.merged(&b))
}
