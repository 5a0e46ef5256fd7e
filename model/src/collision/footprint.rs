//! Queries between footprints. The model's movable objects are upright prisms standing on
//! one table (SE(2) poses), so two of them are apart, touch or overlap exactly as their
//! footprints do seen from above: both rise from the table top, so the closest points of
//! two apart prisms lie at one height, and the least horizontal move that separates two
//! overlapping ones is their footprints' (the vertical one, the lower prism's height, is
//! no way out on a table).
//!
//! Why not parry's 3D queries for these pairs: two prisms of the same height have coplanar
//! tops and bottoms, and parry's EPA then answers a distance of about zero for pairs that
//! overlap by centimetres (two bowls of 0.08 m radius 4 cm apart: 0.0 m, where they
//! overlap by 0.12 m). In 2D every answer here is a closed form.
//!
//! Frames: footprints in their object frames (centred on the centre of friction), poses
//! world-frame on the table; every point and normal returned is world-frame xy (m).

use crate::math::{closest_on_segment, Pose2};
use crate::physics::Footprint;
use nalgebra::Vector2;

/// One point where two footprints touch, overlap or come within a margin, world-frame xy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FootprintContact {
    /// Point on the boundary of `a` (m).
    pub point_a: Vector2<f64>,
    /// Point on the boundary of `b` (m).
    pub point_b: Vector2<f64>,
    /// Unit normal out of `a`, toward `b`.
    pub normal: Vector2<f64>,
    /// Distance between the boundaries along the normal (m): negative when overlapping.
    pub gap: f64,
}

/// The signed distance between footprint `a` at `pose_a` and `b` at `pose_b` (m): how far
/// apart they are, or minus the least distance either must move to come apart.
pub fn gap(a: &Footprint, pose_a: &Pose2, b: &Footprint, pose_b: &Pose2) -> f64 {
    match (Placed::new(a, pose_a), Placed::new(b, pose_b)) {
        (Placed::Circle(ca, ra), Placed::Circle(cb, rb)) => (cb - ca).norm() - ra - rb,
        (Placed::Polygon(p), Placed::Circle(c, r)) | (Placed::Circle(c, r), Placed::Polygon(p)) => {
            point_to_polygon(&p, c).distance - r
        }
        (Placed::Polygon(p), Placed::Polygon(q)) => polygons_gap(&p, &q),
    }
}

/// Appends the contacts of `a` at `pose_a` with `b` at `pose_b` whose gap is at most
/// `margin` (m): one point for a circle, up to two for facing polygon edges (the ends of
/// the stretch where they face each other, which is what lets a flat face push a box
/// straight).
pub fn contacts(
    a: &Footprint,
    pose_a: &Pose2,
    b: &Footprint,
    pose_b: &Pose2,
    margin: f64,
    out: &mut Vec<FootprintContact>,
) {
    match (Placed::new(a, pose_a), Placed::new(b, pose_b)) {
        (Placed::Circle(ca, ra), Placed::Circle(cb, rb)) => {
            let d = cb - ca;
            let distance = d.norm();
            let gap = distance - ra - rb;
            if gap <= margin {
                let normal = if distance > 1e-12 {
                    d / distance
                } else {
                    Vector2::x()
                };
                out.push(FootprintContact {
                    point_a: ca + normal * ra,
                    point_b: cb - normal * rb,
                    normal,
                    gap,
                });
            }
        }
        (Placed::Polygon(p), Placed::Circle(c, r)) => {
            if let Some(contact) = polygon_circle(&p, c, r, margin) {
                out.push(contact);
            }
        }
        (Placed::Circle(c, r), Placed::Polygon(p)) => {
            if let Some(contact) = polygon_circle(&p, c, r, margin) {
                out.push(contact.flipped());
            }
        }
        (Placed::Polygon(p), Placed::Polygon(q)) => polygon_polygon(&p, &q, margin, out),
    }
}

impl FootprintContact {
    /// The same contact seen from the other footprint.
    fn flipped(self) -> FootprintContact {
        FootprintContact {
            point_a: self.point_b,
            point_b: self.point_a,
            normal: -self.normal,
            gap: self.gap,
        }
    }
}

/// A footprint placed on the table: a circle's centre and radius, or a polygon's vertices
/// (counter-clockwise), world frame.
enum Placed {
    Circle(Vector2<f64>, f64),
    Polygon(Vertices),
}

impl Placed {
    fn new(footprint: &Footprint, pose: &Pose2) -> Placed {
        match footprint {
            Footprint::Circle { radius } => Placed::Circle(pose.translation(), *radius),
            Footprint::Polygon { vertices } => Placed::Polygon(Vertices::placed(vertices, pose)),
        }
    }
}

/// Polygons with up to this many vertices (boxes have four) are placed without allocating:
/// validity asks for every pair of neighbouring objects at every step.
const INLINE_VERTICES: usize = 8;

/// A placed polygon's vertices, world frame.
enum Vertices {
    Inline([Vector2<f64>; INLINE_VERTICES], usize),
    Heap(Vec<Vector2<f64>>),
}

impl Vertices {
    fn placed(local: &[Vector2<f64>], pose: &Pose2) -> Vertices {
        if local.len() > INLINE_VERTICES {
            return Vertices::Heap(local.iter().map(|v| pose.point_to_world(*v)).collect());
        }
        let mut inline = [Vector2::zeros(); INLINE_VERTICES];
        for (w, v) in inline.iter_mut().zip(local) {
            *w = pose.point_to_world(*v);
        }
        Vertices::Inline(inline, local.len())
    }
}

impl std::ops::Deref for Vertices {
    type Target = [Vector2<f64>];

    fn deref(&self) -> &[Vector2<f64>] {
        match self {
            Vertices::Inline(v, n) => &v[..*n],
            Vertices::Heap(v) => v,
        }
    }
}

/// Edge `i` of a counter-clockwise polygon: its start and its outward unit normal.
fn edge(polygon: &[Vector2<f64>], i: usize) -> (Vector2<f64>, Vector2<f64>) {
    let start = polygon[i];
    let along = polygon[(i + 1) % polygon.len()] - start;
    let normal = Vector2::new(along.y, -along.x) / along.norm();
    (start, normal)
}

/// Where a point stands to a polygon's boundary.
struct PointToPolygon {
    /// Signed distance (m): positive outside, negative inside.
    distance: f64,
    /// The nearest boundary point (inside: the foot on the nearest edge).
    closest: Vector2<f64>,
    /// Unit normal out of the polygon at `closest`, toward the point when outside.
    normal: Vector2<f64>,
}

fn point_to_polygon(polygon: &[Vector2<f64>], p: Vector2<f64>) -> PointToPolygon {
    // Inside, the nearest edge line is the nearest boundary (its foot lies on the edge).
    let (mut nearest_line, mut line_edge) = (f64::NEG_INFINITY, 0);
    for i in 0..polygon.len() {
        let (start, normal) = edge(polygon, i);
        let s = normal.dot(&(p - start));
        if s > nearest_line {
            (nearest_line, line_edge) = (s, i);
        }
    }
    if nearest_line <= 0.0 {
        let (_, normal) = edge(polygon, line_edge);
        return PointToPolygon {
            distance: nearest_line,
            closest: p - normal * nearest_line,
            normal,
        };
    }
    // Outside: the nearest point of any edge (an edge's interior or a vertex).
    let (mut closest, mut distance2) = (polygon[0], f64::INFINITY);
    for i in 0..polygon.len() {
        let q = closest_on_segment(p, polygon[i], polygon[(i + 1) % polygon.len()]);
        let d2 = (p - q).norm_squared();
        if d2 < distance2 {
            (closest, distance2) = (q, d2);
        }
    }
    let distance = distance2.sqrt();
    let normal = if distance > 1e-12 {
        (p - closest) / distance
    } else {
        edge(polygon, line_edge).1
    };
    PointToPolygon {
        distance,
        closest,
        normal,
    }
}

fn polygon_circle(
    polygon: &[Vector2<f64>],
    centre: Vector2<f64>,
    radius: f64,
    margin: f64,
) -> Option<FootprintContact> {
    let to = point_to_polygon(polygon, centre);
    let gap = to.distance - radius;
    (gap <= margin).then(|| FootprintContact {
        point_a: to.closest,
        point_b: centre - to.normal * radius,
        normal: to.normal,
        gap,
    })
}

/// The largest separation of `b` from one of `a`'s edge lines (the least, over `b`'s
/// vertices, of their distances outward of the line), and that edge. Positive: the line
/// separates the polygons.
fn max_separation(a: &[Vector2<f64>], b: &[Vector2<f64>]) -> (f64, usize) {
    let mut best = (f64::NEG_INFINITY, 0);
    for i in 0..a.len() {
        let (start, normal) = edge(a, i);
        let s = b
            .iter()
            .map(|v| normal.dot(&(v - start)))
            .fold(f64::INFINITY, f64::min);
        if s > best.0 {
            best = (s, i);
        }
    }
    best
}

/// Convex polygons: apart, the least vertex-to-edge distance; overlapping, the largest
/// separation over both polygons' edge normals (minus the penetration depth: the faces
/// of their Minkowski difference are their edges).
fn polygons_gap(a: &[Vector2<f64>], b: &[Vector2<f64>]) -> f64 {
    let s = max_separation(a, b).0.max(max_separation(b, a).0);
    if s <= 0.0 {
        return s;
    }
    closest_points(a, b).2
}

/// The closest points of two convex polygons that are apart: on `a`, on `b`, and their
/// distance.
fn closest_points(a: &[Vector2<f64>], b: &[Vector2<f64>]) -> (Vector2<f64>, Vector2<f64>, f64) {
    let mut best = (a[0], b[0], f64::INFINITY);
    let mut vertices_to_edges = |from: &[Vector2<f64>], to: &[Vector2<f64>], from_is_a: bool| {
        for &v in from {
            for i in 0..to.len() {
                let q = closest_on_segment(v, to[i], to[(i + 1) % to.len()]);
                let d = (v - q).norm();
                if d < best.2 {
                    best = if from_is_a { (v, q, d) } else { (q, v, d) };
                }
            }
        }
    };
    vertices_to_edges(a, b, true);
    vertices_to_edges(b, a, false);
    best
}

/// Which polygon gives the reference edge when both separate about equally (m): `a`,
/// unless `b`'s separation is larger by more than this.
const REFERENCE_TOLERANCE: f64 = 1e-9;

/// Contacts of convex polygons within `margin`: the edge of largest separation is the
/// reference, the other polygon's edge most against its normal the incident edge; the
/// incident edge clipped to the reference edge's span gives up to two points. Apart, the
/// closest pair of points is added when it is nearer (corners that meet beyond each
/// other's edges), so the smallest gap of the contacts is always the polygons' gap.
fn polygon_polygon(
    a: &[Vector2<f64>],
    b: &[Vector2<f64>],
    margin: f64,
    out: &mut Vec<FootprintContact>,
) {
    let (sa, ea) = max_separation(a, b);
    let (sb, eb) = max_separation(b, a);
    if sa.max(sb) > margin {
        return;
    }
    let b_is_reference = sb > sa + REFERENCE_TOLERANCE;
    let (reference, incident, k) = if b_is_reference {
        (b, a, eb)
    } else {
        (a, b, ea)
    };
    let (r0, normal) = edge(reference, k);
    let r1 = reference[(k + 1) % reference.len()];
    let tangent = Vector2::new(-normal.y, normal.x);
    let (lo, hi) = (tangent.dot(&r0), tangent.dot(&r1));
    let j = (0..incident.len())
        .min_by(|&x, &y| {
            let nx = edge(incident, x).1.dot(&normal);
            let ny = edge(incident, y).1.dot(&normal);
            nx.total_cmp(&ny)
        })
        .expect("a polygon has vertices");
    let segment = [incident[j], incident[(j + 1) % incident.len()]];
    let push = |p: Vector2<f64>, out: &mut Vec<FootprintContact>| {
        let gap = normal.dot(&(p - r0));
        if gap > margin {
            return;
        }
        let on_reference = p - normal * gap;
        let contact = FootprintContact {
            point_a: on_reference,
            point_b: p,
            normal,
            gap,
        };
        out.push(if b_is_reference {
            contact.flipped()
        } else {
            contact
        });
    };
    let before = out.len();
    if let Some(clipped) = clip(segment, tangent, lo, hi) {
        for p in clipped {
            push(p, out);
        }
    }
    if sa.max(sb) > 0.0 {
        // Apart: where corners meet beyond each other's edges, the closest pair of points
        // is nearer than the facing stretch; it is a contact too.
        let (pa, pb, distance) = closest_points(a, b);
        let facing = out[before..]
            .iter()
            .map(|c| c.gap)
            .fold(f64::INFINITY, f64::min);
        if distance <= margin && distance < facing - 1e-12 {
            out.push(FootprintContact {
                point_a: pa,
                point_b: pb,
                normal: (pb - pa) / distance,
                gap: distance,
            });
        }
    } else if out.len() == before {
        // Overlapping past the reference edge's span: the incident polygon's deepest vertex.
        let deepest = incident
            .iter()
            .copied()
            .min_by(|x, y| normal.dot(x).total_cmp(&normal.dot(y)))
            .expect("a polygon has vertices");
        push(deepest, out);
    }
}

/// The part of segment `s` whose projection on `tangent` lies within `[lo, hi]`; `None`
/// if no part does.
fn clip(
    s: [Vector2<f64>; 2],
    tangent: Vector2<f64>,
    lo: f64,
    hi: f64,
) -> Option<[Vector2<f64>; 2]> {
    let (t0, t1) = (tangent.dot(&s[0]), tangent.dot(&s[1]));
    if (t0 < lo && t1 < lo) || (t0 > hi && t1 > hi) {
        return None;
    }
    let at = |t: f64| {
        if (t1 - t0).abs() < 1e-15 {
            s[0]
        } else {
            s[0] + (s[1] - s[0]) * ((t - t0) / (t1 - t0))
        }
    };
    let keep = |t: f64, p: Vector2<f64>| {
        if t < lo {
            at(lo)
        } else if t > hi {
            at(hi)
        } else {
            p
        }
    };
    Some([keep(t0, s[0]), keep(t1, s[1])])
}
