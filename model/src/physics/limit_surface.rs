//! The ellipsoidal limit surface of an object sliding on the table.
//!
//! With `f_max = mu_g m g` and `m_max = mu_g m g c`, the ellipsoid is
//! `F^T diag(1/f_max^2, 1/f_max^2, 1/m_max^2) F = 1` and a quasistatic slide has twist
//! `V ∝ A F` with `A = diag(1, 1, 1/c^2)`: only the characteristic length `c` shapes the
//! motion. Mass and support friction set the force scale (reported in newtons).

use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

/// Standard gravity (m/s^2).
pub const GRAVITY: f64 = 9.81;

/// The footprint of a prism on the table, in the object frame (m).
#[derive(Clone, Debug, PartialEq)]
pub enum Footprint {
    /// A disc centred on the object frame's origin.
    Circle {
        /// Radius (m).
        radius: f64,
    },
    /// Convex polygon, counter-clockwise.
    Polygon {
        /// The vertices (m), object frame.
        vertices: Vec<Vector2<f64>>,
    },
}

impl Footprint {
    /// Area (m^2).
    pub fn area(&self) -> f64 {
        match self {
            Footprint::Circle { radius } => std::f64::consts::PI * radius * radius,
            Footprint::Polygon { vertices } => polygon_edges(vertices)
                .map(|(a, b)| 0.5 * cross(a, b))
                .sum(),
        }
    }

    /// Area centroid (m); the centre of friction under uniform pressure.
    pub fn centroid(&self) -> Vector2<f64> {
        match self {
            Footprint::Circle { .. } => Vector2::zeros(),
            Footprint::Polygon { vertices } => {
                let sum: Vector2<f64> = polygon_edges(vertices)
                    .map(|(a, b)| (a + b) * cross(a, b))
                    .sum();
                sum / (6.0 * self.area())
            }
        }
    }

    /// This footprint scaled by `scale` about its centroid: with `scale` = 1 -
    /// `physics.tipping_margin`, the region the tipping check keeps the support pressure
    /// in.
    pub fn scaled_about_centroid(&self, scale: f64) -> Footprint {
        match self {
            Footprint::Circle { radius } => Footprint::Circle {
                radius: scale * radius,
            },
            Footprint::Polygon { vertices } => {
                let centroid = self.centroid();
                Footprint::Polygon {
                    vertices: vertices
                        .iter()
                        .map(|v| centroid + scale * (v - centroid))
                        .collect(),
                }
            }
        }
    }

    /// Is the point `p` (object frame, m) inside the footprint or on its edge?
    pub fn contains(&self, p: Vector2<f64>) -> bool {
        match self {
            Footprint::Circle { radius } => p.norm() <= *radius,
            Footprint::Polygon { vertices } => {
                polygon_edges(vertices).all(|(a, b)| cross(b - a, p - a) >= 0.0)
            }
        }
    }

    /// The least and the greatest distance (m) from the centroid to an edge's line: the
    /// lever of the weight about the edge a push tips the prism over, for the push
    /// toward that edge (a disc: its radius, both). A push that slides the prism at height
    /// `h` tips it about an edge at lever `b` when `h > b / mu_g` (`physics.md`,
    /// "Tipping").
    pub fn half_widths(&self) -> (f64, f64) {
        match self {
            Footprint::Circle { radius } => (*radius, *radius),
            Footprint::Polygon { vertices } => {
                let g = self.centroid();
                polygon_edges(vertices)
                    .map(|(a, b)| cross(b - a, g - a) / (b - a).norm())
                    .fold((f64::INFINITY, 0.0), |(lo, hi), d| (lo.min(d), hi.max(d)))
            }
        }
    }

    /// Characteristic length `c = (1/A) ∫ |r| dA` (m) about the origin, for uniform
    /// pressure.
    ///
    /// For a polygon, each edge contributes the triangle it spans with the origin: with
    /// `d` the edge line's distance from the origin and `s` the position along it,
    /// `∫|r| dA = (1/6) [d s |p| + d^3 asinh(s/d)]` between the edge's end points.
    pub fn characteristic_length(&self) -> f64 {
        match self {
            Footprint::Circle { radius } => 2.0 * radius / 3.0,
            Footprint::Polygon { vertices } => {
                let integral: f64 = polygon_edges(vertices)
                    .map(|(a, b)| {
                        let edge = b - a;
                        let t = edge / edge.norm();
                        let d = cross(t, a).abs();
                        if d < 1e-12 {
                            return 0.0;
                        }
                        let primitive = |p: Vector2<f64>| {
                            let s = p.dot(&t);
                            d * s * p.norm() + d.powi(3) * (s / d).asinh()
                        };
                        cross(a, b).signum() * (primitive(b) - primitive(a)) / 6.0
                    })
                    .sum();
                integral / self.area()
            }
        }
    }
}

fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

fn polygon_edges(
    vertices: &[Vector2<f64>],
) -> impl Iterator<Item = (Vector2<f64>, Vector2<f64>)> + '_ {
    (0..vertices.len()).map(move |i| (vertices[i], vertices[(i + 1) % vertices.len()]))
}

/// An object's limit surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LimitSurface {
    /// Characteristic length c (m).
    pub c: f64,
    /// Largest friction force the table can exert, `mu_g m g` (N).
    pub f_max: f64,
    /// Centre of friction, object frame (m): the footprint's centroid (the origin) under
    /// a uniform pressure; elsewhere when the pressure is not (robustness perturbs it).
    pub centre: Vector2<f64>,
}

impl LimitSurface {
    /// The motion mapping `A = diag(1, 1, 1/c^2)` (twist ∝ A wrench).
    pub fn mobility(&self) -> Matrix3<f64> {
        Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 1.0 / (self.c * self.c)))
    }
}

/// A footprint sampled on a grid of equal cells, for integrals over a support pressure
/// that is not uniform.
#[derive(Clone, Debug, PartialEq)]
pub struct SupportGrid {
    /// Cell centres inside the footprint, object frame (m).
    points: Vec<Vector2<f64>>,
    /// Their mean (m): the centroid.
    centroid: Vector2<f64>,
    /// Inverse of their covariance (1/m^2).
    inverse_spread: Matrix2<f64>,
    /// Mean distance of the points from the centroid under uniform pressure (m).
    uniform_c: f64,
}

/// Cells across the footprint's bounding box on a side.
const GRID_CELLS: usize = 16;

impl SupportGrid {
    /// The grid of cells over `footprint` that carries its support pressure.
    pub fn new(footprint: &Footprint) -> Self {
        let (lo, hi) = match footprint {
            Footprint::Circle { radius } => (Vector2::repeat(-radius), Vector2::repeat(*radius)),
            Footprint::Polygon { vertices } => vertices.iter().fold(
                (
                    Vector2::repeat(f64::INFINITY),
                    Vector2::repeat(f64::NEG_INFINITY),
                ),
                |(lo, hi), v| (lo.inf(v), hi.sup(v)),
            ),
        };
        let cell = (hi - lo) / GRID_CELLS as f64;
        let points: Vec<Vector2<f64>> = (0..GRID_CELLS * GRID_CELLS)
            .map(|k| {
                let (i, j) = (k % GRID_CELLS, k / GRID_CELLS);
                lo + Vector2::new(cell.x * (i as f64 + 0.5), cell.y * (j as f64 + 0.5))
            })
            .filter(|&p| footprint.contains(p))
            .collect();
        let n = points.len() as f64;
        let centroid = points.iter().sum::<Vector2<f64>>() / n;
        let spread = points
            .iter()
            .map(|p| (p - centroid) * (p - centroid).transpose())
            .sum::<Matrix2<f64>>()
            / n;
        let uniform_c = points.iter().map(|p| (p - centroid).norm()).sum::<f64>() / n;
        Self {
            inverse_spread: spread.try_inverse().unwrap_or_else(Matrix2::zeros),
            points,
            centroid,
            uniform_c,
        }
    }

    /// The planar (linear) pressure whose centre is the centroid moved by `shift` (m),
    /// clipped where it would pull: its centre of friction relative to the uniform one
    /// (m), and its characteristic length `c` relative to the uniform one. The table
    /// carrying a push at height presses hardest under the leading edge; friction
    /// concentrated there resists turning less.
    pub fn loaded(&self, shift: Vector2<f64>) -> (Vector2<f64>, f64) {
        let gradient = self.inverse_spread * shift;
        // p = max(0, level + gradient . (r - r_G)): with level 1 its centre is the target,
        // unless it would pull somewhere (beyond the kern). Clipped, its centre falls
        // short; lowering the level moves the zero line toward the loaded edge and the
        // centre out to it, monotonically: bisection.
        let weight =
            |level: f64, p: &Vector2<f64>| (level + gradient.dot(&(p - self.centroid))).max(0.0);
        let centre_of = |level: f64| {
            let (mut total, mut moment) = (0.0, Vector2::zeros());
            for p in &self.points {
                let w = weight(level, p);
                total += w;
                moment += (p - self.centroid) * w;
            }
            (moment / total, total)
        };
        let target = shift.norm();
        let mut level = 1.0;
        if centre_of(1.0).0.norm() < target * (1.0 - 1e-4) {
            let peak = self
                .points
                .iter()
                .map(|p| gradient.dot(&(p - self.centroid)))
                .fold(f64::NEG_INFINITY, f64::max);
            let (mut low, mut high) = (-peak * (1.0 - 1e-9), 1.0);
            for _ in 0..14 {
                level = 0.5 * (low + high);
                if centre_of(level).0.norm() < target {
                    high = level;
                } else {
                    low = level;
                }
            }
        }
        let (centre, total) = centre_of(level);
        let c = self
            .points
            .iter()
            .map(|p| weight(level, p) * (p - self.centroid - centre).norm())
            .sum::<f64>()
            / total;
        (centre, c / self.uniform_c)
    }
}

/// [`SupportGrid::loaded`]'s `c` ratio tabulated over the direction and size of the
/// pressure centre's shift, for the propagator: a lookup instead of an integral per step.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadedSupport {
    /// Per shift direction (evenly spaced from +x counter-clockwise; one for a disc), how
    /// far the centre of pressure can move (m): the farthest grid point.
    reach: Vec<f64>,
    /// Per direction, the `c` ratio at `k / SHIFT_SAMPLES` of the reach, k =
    /// 0..=SHIFT_SAMPLES.
    ratios: Vec<[f64; SHIFT_SAMPLES + 1]>,
}

const SHIFT_SAMPLES: usize = 16;

impl LoadedSupport {
    /// The characteristic-length ratios of `footprint` for every shift of the pressure's
    /// centre.
    pub fn new(footprint: &Footprint) -> Self {
        let grid = SupportGrid::new(footprint);
        let directions = match footprint {
            Footprint::Circle { .. } => 1,
            Footprint::Polygon { .. } => 32,
        };
        let unit = |i: usize| {
            let angle = std::f64::consts::TAU * i as f64 / directions as f64;
            Vector2::new(angle.cos(), angle.sin())
        };
        let reach: Vec<f64> = (0..directions)
            .map(|i| {
                grid.points
                    .iter()
                    .map(|p| unit(i).dot(&(p - grid.centroid)))
                    .fold(0.0, f64::max)
            })
            .collect();
        let ratios = (0..directions)
            .map(|i| {
                std::array::from_fn(|k| {
                    // Just short of the edge, where the pressure is still spread over cells.
                    let fraction = (k as f64 / SHIFT_SAMPLES as f64).min(0.97);
                    grid.loaded(unit(i) * fraction * reach[i]).1
                })
            })
            .collect();
        Self { reach, ratios }
    }

    /// `c` relative to the uniform pressure's when the centre of pressure (and so of
    /// friction) has moved by `shift` (m) from the centroid; interpolated.
    pub fn c_ratio(&self, shift: Vector2<f64>) -> f64 {
        let size = shift.norm();
        if size == 0.0 {
            return 1.0;
        }
        let at = |i: usize| {
            let f = (size / self.reach[i]).min(1.0) * SHIFT_SAMPLES as f64;
            let k = (f.floor() as usize).min(SHIFT_SAMPLES - 1);
            let r = &self.ratios[i];
            r[k] + (f - k as f64) * (r[k + 1] - r[k])
        };
        let turn = shift.y.atan2(shift.x).rem_euclid(std::f64::consts::TAU);
        let directions = self.reach.len();
        let a = turn / std::f64::consts::TAU * directions as f64;
        let i = (a.floor() as usize).min(directions - 1);
        let t = a - i as f64;
        (1.0 - t) * at(i) + t * at((i + 1) % directions)
    }
}
