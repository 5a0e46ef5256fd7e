//! FCL is the independent oracle for pushplan's collision code: random link and object
//! poses must give the same collide / no-collide verdict and separation distances within
//! 1e-6 m.
//!
//! Penetration depths are checked (within 1e-4 m) against an exact oracle computed here
//! from the shapes' support functions alone, because FCL 0.7's depths are not exact: its
//! box-box routine overestimates (0.05976 m for an exact 0.05929 m), GJK/EPA (GST_INDEP)
//! returns negative depths for box-cylinder pairs, and libccd's MPR is off by ~1e-3 m in
//! most overlapping cases. The test prints how often FCL's depth disagrees.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use pushplan::collision::query::{intersects, signed_distance};
use pushplan::collision::{Geometry, Primitive};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use pushplan_fcl_oracle::fcl;

/// One shape in both descriptions.
struct Case {
    primitive: Primitive,
    fcl_kind: &'static str,
    dims: Vec<f64>,
    vertices: Vec<f64>,
}

fn shapes() -> Vec<Case> {
    let pentagon: Vec<[f64; 2]> = (0..5)
        .map(|i| {
            let a = i as f64 * 2.0 * std::f64::consts::PI / 5.0;
            [0.06 * a.cos(), 0.06 * a.sin()]
        })
        .collect();
    let height = 0.12;
    let prism_points = pentagon
        .iter()
        .flat_map(|p| {
            [
                Point3::new(p[0], p[1], 0.0),
                Point3::new(p[0], p[1], height),
            ]
        })
        .collect();
    vec![
        Case {
            primitive: Primitive::Box {
                size: Vector3::new(0.1, 0.08, 0.14),
            },
            fcl_kind: "box",
            dims: vec![0.1, 0.08, 0.14],
            vertices: vec![],
        },
        Case {
            primitive: Primitive::Cylinder {
                radius: 0.04,
                length: 0.12,
            },
            fcl_kind: "cylinder",
            dims: vec![0.04, 0.12],
            vertices: vec![],
        },
        Case {
            primitive: Primitive::Sphere { radius: 0.05 },
            fcl_kind: "sphere",
            dims: vec![0.05],
            vertices: vec![],
        },
        Case {
            primitive: Primitive::Capsule {
                radius: 0.045,
                length: 0.16,
            },
            fcl_kind: "capsule",
            dims: vec![0.045, 0.16],
            vertices: vec![],
        },
        Case {
            primitive: Primitive::ConvexHull {
                points: prism_points,
            },
            fcl_kind: "prism",
            dims: vec![height],
            vertices: pentagon.iter().flatten().copied().collect(),
        },
    ]
}

fn random_pose(rng: &mut ChaCha8Rng) -> Isometry3<f64> {
    let t = Translation3::new(
        rng.random_range(-0.12..0.12),
        rng.random_range(-0.12..0.12),
        rng.random_range(-0.1..0.1),
    );
    let axis = Vector3::new(
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
    );
    let r = UnitQuaternion::from_scaled_axis(
        axis.normalize() * rng.random_range(0.0..std::f64::consts::PI),
    );
    Isometry3::from_parts(t, r)
}

fn fcl_shape(case: &Case, pose: &Isometry3<f64>) -> fcl::FclShape {
    let q = pose.rotation.quaternion();
    fcl::FclShape {
        kind: case.fcl_kind.into(),
        dims: case.dims.clone(),
        vertices: case.vertices.clone(),
        pose: vec![
            pose.translation.x,
            pose.translation.y,
            pose.translation.z,
            q.w,
            q.i,
            q.j,
            q.k,
        ],
    }
}

#[test]
fn pushplan_collision_queries_agree_with_fcl() {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let shapes = shapes();
    let (mut apart, mut overlapping, mut fcl_depth_off) = (0, 0, 0);
    for a in &shapes {
        for b in &shapes {
            let (ga, gb) = (
                Geometry::new(&a.primitive, Isometry3::identity()).unwrap(),
                Geometry::new(&b.primitive, Isometry3::identity()).unwrap(),
            );
            for _ in 0..150 {
                let (pa, pb) = (random_pose(&mut rng), random_pose(&mut rng));
                let oracle = fcl::fcl_query(&fcl_shape(a, &pa), &fcl_shape(b, &pb));
                let ours = signed_distance(&ga, &pa, &gb, &pb, f64::INFINITY).unwrap();
                let hit = intersects(&ga, &pa, &gb, &pb);
                let pair = format!("{} vs {}", a.fcl_kind, b.fcl_kind);
                if ours.abs() < 1e-6 {
                    continue; // touching: either verdict is right
                }
                assert_eq!(
                    hit, oracle.collide,
                    "verdict, {pair}: ours {ours}, fcl {}",
                    oracle.distance
                );
                if ours > 0.0 {
                    apart += 1;
                    assert!(
                        (ours - oracle.distance).abs() < 1e-6,
                        "distance, {pair}: ours {ours}, fcl {}",
                        oracle.distance
                    );
                } else {
                    overlapping += 1;
                    let exact = -support_distance(a, &pa, b, &pb);
                    assert!(
                        (-ours - exact).abs() < 1e-4,
                        "depth, {pair}: ours {}, exact {exact}",
                        -ours
                    );
                    if (oracle.depth - exact).abs() >= 1e-4 {
                        fcl_depth_off += 1;
                    }
                }
            }
        }
    }
    eprintln!(
        "{overlapping} overlapping pairs; FCL's depth is off by 1e-4 m or more in {fcl_depth_off}"
    );
    // Both regimes are well represented.
    assert!(
        apart > 500 && overlapping > 500,
        "apart {apart}, overlapping {overlapping}"
    );
}

/// Support function `h(n) = max_{p in shape} n . p` of a shape at `pose`, in closed form.
fn support(case: &Case, pose: &Isometry3<f64>, n: &Vector3<f64>) -> f64 {
    let c = pose.translation.vector.dot(n);
    let local = pose.rotation.inverse() * n;
    let d = &case.dims;
    c + match case.fcl_kind {
        "box" => (0..3).map(|i| d[i] / 2.0 * local[i].abs()).sum::<f64>(),
        "cylinder" => d[0] * local.xy().norm() + d[1] / 2.0 * local.z.abs(),
        "sphere" => d[0] * local.norm(),
        "capsule" => d[0] * local.norm() + d[1] / 2.0 * local.z.abs(),
        "prism" => case
            .vertices
            .chunks(2)
            .flat_map(|v| {
                [
                    v[0] * local.x + v[1] * local.y,
                    v[0] * local.x + v[1] * local.y + d[0] * local.z,
                ]
            })
            .fold(f64::NEG_INFINITY, f64::max),
        other => panic!("{other}"),
    }
}

/// Signed distance of two convex shapes from their support functions alone: the largest
/// gap `-h_A(n) - h_B(-n)` over unit directions n is the distance when they are apart and
/// minus the penetration depth when they overlap. Dense directions, then pattern search.
fn support_distance(a: &Case, pa: &Isometry3<f64>, b: &Case, pb: &Isometry3<f64>) -> f64 {
    let gap = |n: &Vector3<f64>| -support(a, pa, n) - support(b, pb, &-n);
    let count = 20_000;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut starts: Vec<(f64, Vector3<f64>)> = (0..count)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
            let r = (1.0 - z * z).sqrt();
            let n = Vector3::new(
                r * (golden * i as f64).cos(),
                r * (golden * i as f64).sin(),
                z,
            );
            (gap(&n), n)
        })
        .collect();
    starts.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut best_gap = f64::NEG_INFINITY;
    for &(start_gap, start) in starts.iter().take(8) {
        // Pattern search with probes turned by the golden angle each round (the gap has
        // ridges where a fixed probe pattern stalls).
        let (mut n0, mut g0, mut step, mut turn) = (start, start_gap, 0.02, 0.0f64);
        while step > 1e-12 {
            let helper = if n0.x.abs() < 0.9 {
                Vector3::x()
            } else {
                Vector3::y()
            };
            let u = n0.cross(&helper).normalize();
            let v = n0.cross(&u);
            turn += 2.399_963_229_728_653;
            let mut improved = false;
            for k in 0..12 {
                let angle = turn + k as f64 * std::f64::consts::PI / 6.0;
                let n = (n0 + (u * angle.cos() + v * angle.sin()) * step).normalize();
                let g = gap(&n);
                if g > g0 {
                    (n0, g0, improved) = (n, g, true);
                }
            }
            if !improved {
                step *= 0.5;
            }
        }
        best_gap = best_gap.max(g0);
    }
    best_gap
}
