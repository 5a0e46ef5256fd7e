//! Collision meshes in STL, OBJ and COLLADA; hull simplification; the shipped mesh robot.

use crate::common;

use nalgebra::{Isometry3, Point3, Vector3};
use parry3d_f64::bounding_volume::BoundingVolume;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::ConvexPolyhedron;
use pushplan::collision::Primitive;
use pushplan::robot::mesh::{
    load_collision_mesh, load_convex_mesh, simplify_hull, HULL_TOLERANCE, MAX_HULL_VERTICES,
};
use pushplan::robot::urdf::load_urdf;
use std::path::Path;

/// The 8 corners and 12 triangles of an axis-aligned box with half extents `h`.
pub(crate) fn box_mesh(h: [f64; 3]) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let corners = (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { -h[0] } else { h[0] },
                if i & 2 == 0 { -h[1] } else { h[1] },
                if i & 4 == 0 { -h[2] } else { h[2] },
            ]
        })
        .collect();
    let faces = vec![
        [0, 2, 3],
        [0, 3, 1],
        [4, 5, 7],
        [4, 7, 6],
        [0, 1, 5],
        [0, 5, 4],
        [2, 6, 7],
        [2, 7, 3],
        [0, 4, 6],
        [0, 6, 2],
        [1, 3, 7],
        [1, 7, 5],
    ];
    (corners, faces)
}

fn obj_text((vertices, faces): &(Vec<[f64; 3]>, Vec<[usize; 3]>)) -> String {
    let mut text = String::from("# a box\nmtllib missing.mtl\no box\n");
    for v in vertices {
        text += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for f in faces {
        text += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    text
}

/// COLLADA with the given unit (metres per unit) and up axis; the vertices are written as
/// given (already in the file's frame and unit).
fn dae_text((vertices, faces): &(Vec<[f64; 3]>, Vec<[usize; 3]>), meter: f64, up: &str) -> String {
    let positions: Vec<String> = vertices
        .iter()
        .map(|v| format!("{} {} {}", v[0], v[1], v[2]))
        .collect();
    let indices: Vec<String> = faces
        .iter()
        .map(|f| format!("{} {} {}", f[0], f[1], f[2]))
        .collect();
    format!(
        r##"<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
 <asset><unit meter="{meter}"/>{up}</asset>
 <library_geometries><geometry id="g"><mesh>
  <source id="p"><float_array id="pa" count="{count}">{positions}</float_array>
   <technique_common><accessor source="#pa" count="{n}" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <triangles count="{triangles}"><input semantic="VERTEX" source="#v" offset="0"/><p>{indices}</p></triangles>
 </mesh></geometry></library_geometries>
 <library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
 <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"##,
        count = 3 * vertices.len(),
        n = vertices.len(),
        positions = positions.join(" "),
        triangles = faces.len(),
        indices = indices.join(" "),
    )
}

/// The axis-aligned bounds (min, max) of a loaded mesh's hull.
fn bounds(path: &Path, scale: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let Primitive::ConvexHull { points } = load_convex_mesh(path, scale).unwrap() else {
        panic!("a mesh loads as a convex hull");
    };
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

fn assert_bounds(found: ([f64; 3], [f64; 3]), half: [f64; 3], what: &str) {
    for k in 0..3 {
        assert!(
            (found.0[k] + half[k]).abs() < 1e-6 && (found.1[k] - half[k]).abs() < 1e-6,
            "{what}: bounds {found:?}, expected ±{half:?}"
        );
    }
}

/// A box of half extents (0.05, 0.1, 0.2) m written as OBJ in metres and as COLLADA in
/// millimetres with each up axis: every file loads as the same box in the URDF's z-up
/// frame (COLLADA's Y_UP turns (x, y, z) to (x, -z, y), X_UP to (-y, -z, x)).
#[test]
fn obj_and_collada_meshes_load_in_metres_with_z_up() {
    let scratch = common::Scratch::new("test-mesh-formats");
    let half = [0.05, 0.1, 0.2];

    let obj = scratch.join("box.obj");
    std::fs::write(&obj, obj_text(&box_mesh(half))).unwrap();
    assert_bounds(bounds(&obj, [1.0; 3]), half, "OBJ");
    assert_bounds(bounds(&obj, [2.0, 1.0, 0.5]), [0.1, 0.1, 0.1], "OBJ scaled");

    // In the file's frame, in mm: Z_UP keeps the axes; Y_UP's file y is our z, and our y
    // is its -z; X_UP's file x is our z, our x its -y, our y its -z.
    let mm = |h: [f64; 3]| h.map(|v| v * 1000.0);
    for (up, file_half) in [
        ("<up_axis>Z_UP</up_axis>", [half[0], half[1], half[2]]),
        ("<up_axis>Y_UP</up_axis>", [half[0], half[2], half[1]]),
        ("", [half[0], half[2], half[1]]),
        ("<up_axis>X_UP</up_axis>", [half[2], half[0], half[1]]),
    ] {
        let dae = scratch.join("box.dae");
        std::fs::write(&dae, dae_text(&box_mesh(mm(file_half)), 0.001, up)).unwrap();
        assert_bounds(bounds(&dae, [1.0; 3]), half, &format!("COLLADA {up:?}"));
    }

    let ply = scratch.join("box.ply");
    std::fs::write(&ply, "ply\n").unwrap();
    let message = load_convex_mesh(&ply, [1.0; 3]).unwrap_err().to_string();
    assert!(
        message.contains("box.ply") && message.contains("OBJ") && message.contains("COLLADA"),
        "{message}"
    );
    let broken = scratch.join("broken.dae");
    std::fs::write(&broken, "<COLLADA><library_geometries>").unwrap();
    let message = load_convex_mesh(&broken, [1.0; 3]).unwrap_err().to_string();
    assert!(message.contains("broken.dae"), "{message}");
}

/// A U-shaped block, 0.1 m high: a 0.3 x 0.2 m outline with a 0.1 m wide, 0.15 m deep
/// notch from its far side (counter-clockwise from (-0.15, 0)), extruded as a closed mesh
/// whose triangles face outward. With `caps: false`, only its walls (an open surface).
fn u_block(caps: bool) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let outline = [
        [-0.15, 0.0],
        [0.15, 0.0],
        [0.15, 0.2],
        [0.05, 0.2],
        [0.05, 0.05],
        [-0.05, 0.05],
        [-0.05, 0.2],
        [-0.15, 0.2],
    ];
    let n = outline.len();
    // Bottom ring 0..n at z = 0, top ring n..2n at z = 0.1.
    let vertices = [0.0, 0.1]
        .iter()
        .flat_map(|&z| outline.iter().map(move |p| [p[0], p[1], z]))
        .collect();
    let mut faces = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push([i, j, n + j]);
        faces.push([i, n + j, n + i]);
    }
    if caps {
        // The outline cut into six triangles by hand (each inside the U), counter-clockwise.
        for [a, b, c] in [
            [0, 1, 4],
            [1, 2, 4],
            [2, 3, 4],
            [0, 4, 5],
            [0, 5, 7],
            [5, 6, 7],
        ] {
            faces.push([n + a, n + b, n + c]);
            faces.push([a, c, b]);
        }
    }
    (vertices, faces)
}

/// A concave mesh collides as convex parts that keep out of its notch and still cover it;
/// a convex mesh, and an open surface whose enclosed volume means nothing, as their hull.
/// The oracle is the U's construction: its notch, its vertices, its volume.
#[test]
fn a_concave_mesh_collides_as_convex_parts_that_leave_its_notch_free() {
    let scratch = common::Scratch::new("test-mesh-concave");
    let u = scratch.join("u.obj");
    std::fs::write(&u, obj_text(&u_block(true))).unwrap();
    let parts = load_collision_mesh(&u, [1.0; 3]).unwrap();
    assert!(parts.len() >= 2, "{} part(s)", parts.len());
    let polyhedra: Vec<ConvexPolyhedron> = parts
        .iter()
        .map(|part| {
            let Primitive::ConvexHull { points } = part else {
                panic!("a part is a convex hull");
            };
            assert!(points.len() <= MAX_HULL_VERTICES);
            ConvexPolyhedron::from_convex_hull(points).unwrap()
        })
        .collect();
    let distance = |p: Point3<f64>| {
        polyhedra
            .iter()
            .map(|h| h.distance_to_local_point(&p, true))
            .fold(f64::INFINITY, f64::min)
    };
    // The notch's middle, 5 cm from either arm: inside the U's hull, outside every part.
    let notch = Point3::new(0.0, 0.15, 0.05);
    let Primitive::ConvexHull { points } = load_convex_mesh(&u, [1.0; 3]).unwrap() else {
        panic!("a mesh loads as a convex hull");
    };
    let hull = ConvexPolyhedron::from_convex_hull(&points).unwrap();
    assert!(hull.contains_local_point(&notch));
    assert!(distance(notch) > 0.03, "{} m", distance(notch));
    // Every corner of the U lies in a part (within the simplification's tolerance).
    for v in &u_block(true).0 {
        let d = distance(Point3::from(*v));
        assert!(d <= HULL_TOLERANCE + 1e-9, "corner {v:?} is {d} m outside");
    }
    // The parts enclose little more than the U's own 0.0045 m^3 (hull: 0.006 m^3).
    let volume: f64 = polyhedra
        .iter()
        .map(|h| {
            use parry3d_f64::shape::Shape;
            h.mass_properties(1.0).mass()
        })
        .sum();
    assert!((0.0044..0.0052).contains(&volume), "{volume} m^3");
    // The same mesh with a comment added (other bytes: decomposed again, not taken from
    // what the process kept): the same parts, bit for bit.
    let again = scratch.join("u_again.obj");
    std::fs::write(&again, obj_text(&u_block(true)) + "# again\n").unwrap();
    assert_eq!(parts, load_collision_mesh(&again, [1.0; 3]).unwrap());

    // A box is its hull; so are the U's walls without their caps (an open surface).
    let cuboid = scratch.join("box.obj");
    std::fs::write(&cuboid, obj_text(&box_mesh([0.05, 0.1, 0.2]))).unwrap();
    let walls = scratch.join("walls.obj");
    std::fs::write(&walls, obj_text(&u_block(false))).unwrap();
    for path in [&cuboid, &walls] {
        assert_eq!(
            load_collision_mesh(path, [1.0; 3]).unwrap(),
            vec![load_convex_mesh(path, [1.0; 3]).unwrap()],
            "{}",
            path.display()
        );
    }

    // In a URDF, the link holds one geometry per part.
    let urdf = scratch.join("u.urdf");
    std::fs::write(
        &urdf,
        r#"<robot name="u"><link name="base"><collision><geometry><mesh filename="u.obj"/></geometry></collision></link>
<link name="tip"><collision><geometry><sphere radius="0.01"/></geometry></collision></link>
<joint name="j" type="revolute"><parent link="base"/><child link="tip"/><axis xyz="0 0 1"/><origin xyz="0 0 0.3"/>
<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"#,
    )
    .unwrap();
    let chain = load_urdf(&urdf, "tip", Isometry3::identity()).unwrap();
    let base = chain.links.iter().find(|l| l.name == "base").unwrap();
    assert_eq!(base.geometry.len(), parts.len());
}

/// A COLLADA file whose indices point past its arrays (mesh-loader panics on it; the model
/// catches the panic): the command refuses the robot naming the mesh, and prints no panic.
#[test]
fn a_collada_mesh_that_panics_its_reader_is_refused_without_a_panic_message() {
    let scratch = common::Scratch::new("test-mesh-collada-panic");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::create_dir_all(scratch.join("meshes/wam7")).unwrap();
    for entry in std::fs::read_dir(root.join("robots/meshes/wam7")).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(
            &path,
            scratch.join("meshes/wam7").join(path.file_name().unwrap()),
        )
        .unwrap();
    }
    let good = dae_text(
        &box_mesh([0.05, 0.05, 0.05]),
        1.0,
        "<up_axis>Z_UP</up_axis>",
    );
    let start = good.find("<p>").unwrap() + 3;
    let end = good.find("</p>").unwrap();
    // As many indices as the triangles need, the last past the 8 vertices.
    let mut indices: Vec<&str> = good[start..end].split(' ').collect();
    *indices.last_mut().unwrap() = "99999";
    let bad = format!("{}{}{}", &good[..start], indices.join(" "), &good[end..]);
    std::fs::write(scratch.join("meshes/wam7/wam_link2.dae"), bad).unwrap();
    std::fs::copy(root.join("robots/wam7_mesh.urdf"), scratch.join("wam.urdf")).unwrap();
    let scene = std::fs::read_to_string(root.join("scenes/herb_single_object.yaml"))
        .unwrap()
        .replace("urdf: ../robots/wam7.urdf", "urdf: wam.urdf");
    std::fs::write(scratch.join("s.yaml"), scene).unwrap();
    let (code, stdout, stderr) = common::pushplan_in(scratch.path(), &["check", "s.yaml"]);
    assert_eq!(code, 2, "{stdout}{stderr}");
    assert!(
        stderr.contains("wam_link2.dae") && stderr.contains("COLLADA indices beyond the arrays"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// A UV sphere of radius 0.06 m with 64 × 32 facets (1 986 vertices).
fn fine_sphere() -> Vec<Point3<f64>> {
    let mut points = vec![Point3::new(0.0, 0.0, 0.06), Point3::new(0.0, 0.0, -0.06)];
    for ring in 1..32 {
        let polar = std::f64::consts::PI * ring as f64 / 32.0;
        for s in 0..64 {
            let a = 2.0 * std::f64::consts::PI * s as f64 / 64.0;
            points.push(Point3::new(
                0.06 * polar.sin() * a.cos(),
                0.06 * polar.sin() * a.sin(),
                0.06 * polar.cos(),
            ));
        }
    }
    points
}

/// The support function h(d) = max over points of p · d.
fn support(points: &[Point3<f64>], d: &Vector3<f64>) -> f64 {
    points
        .iter()
        .map(|p| p.coords.dot(d))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The Hausdorff distance of two nested convex sets is the largest difference of their
/// support functions over unit directions: sampled densely, it checks the simplifier's
/// own measure (point-to-hull distances) by another method.
#[test]
fn simplified_hulls_keep_few_vertices_within_their_measured_error() {
    let sphere = fine_sphere();
    let simplified = simplify_hull(&sphere, HULL_TOLERANCE, MAX_HULL_VERTICES).unwrap();
    assert!(simplified.points.len() <= MAX_HULL_VERTICES);
    assert!(
        simplified.exact_vertices > 1900,
        "{}",
        simplified.exact_vertices
    );
    assert!(simplified
        .points
        .iter()
        .all(|p| sphere.iter().any(|q| (p - q).norm() < 1e-12)));

    // Fibonacci directions over the sphere.
    let n = 20_000;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut largest_gap = 0.0_f64;
    for i in 0..n {
        let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
        let r = (1.0 - z * z).sqrt();
        let d = Vector3::new(
            r * (golden * i as f64).cos(),
            r * (golden * i as f64).sin(),
            z,
        );
        let gap = support(&sphere, &d) - support(&simplified.points, &d);
        assert!(
            gap > -1e-12,
            "the simplified hull lies inside the exact one"
        );
        largest_gap = largest_gap.max(gap);
    }
    assert!(
        largest_gap <= simplified.error + 1e-9 && largest_gap >= 0.9 * simplified.error,
        "support functions differ by up to {largest_gap} m; the simplifier measured {} m",
        simplified.error
    );
    // A sphere needs many vertices: 64 of them leave a few millimetres on a 6 cm ball.
    assert!(simplified.error < 0.004, "{}", simplified.error);

    // A box with points on its faces simplifies to its 8 corners, exactly.
    let mut cube: Vec<Point3<f64>> = box_mesh([0.1, 0.2, 0.3])
        .0
        .iter()
        .map(|v| Point3::from(*v))
        .collect();
    cube.extend((0..50).map(|i| Point3::new(0.1, -0.2 + 0.008 * i as f64, 0.01 * (i % 7) as f64)));
    let box_hull = simplify_hull(&cube, HULL_TOLERANCE, MAX_HULL_VERTICES).unwrap();
    assert_eq!(box_hull.points.len(), 8);
    assert!(box_hull.error < 1e-12, "{}", box_hull.error);
}

/// `robots/wam7_mesh.urdf` (examples/mesh_robot.rs: OBJ in metres, COLLADA in mm with y
/// up) is the WAM of `robots/wam7.urdf` tessellated: each link's bounds, in any pose,
/// match the primitive link's (parry's own shapes) within the tessellation's sagitta and
/// the hull tolerance.
#[test]
fn the_shipped_mesh_robot_matches_the_primitive_one() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("robots");
    let primitive = load_urdf(&root.join("wam7.urdf"), "hand", Isometry3::identity()).unwrap();
    let mesh = load_urdf(&root.join("wam7_mesh.urdf"), "hand", Isometry3::identity()).unwrap();
    assert_eq!(primitive.links.len(), mesh.links.len());
    let pose = Isometry3::new(Vector3::new(0.3, -0.2, 0.5), Vector3::new(0.4, -0.7, 1.1));
    for (p, m) in primitive.links.iter().zip(&mesh.links) {
        assert_eq!(p.geometry.len(), m.geometry.len(), "{}", p.name);
        for (gp, gm) in p.geometry.iter().zip(&m.geometry) {
            // parry's exact boxes (a hull's own `aabb` may be a turned, larger box).
            let exact =
                |g: &pushplan::collision::Geometry| g.shape.compute_aabb(&g.world_pose(&pose));
            let (a, b) = (exact(gp), exact(gm));
            assert!(
                gm.aabb(&pose).contains(&b),
                "the broad phase's box holds the hull"
            );
            let gap = (a.mins - b.mins)
                .abs()
                .max()
                .max((a.maxs - b.maxs).abs().max());
            // A 32-segment circle's chord sits r (1 - cos(pi/32)) = 0.3 mm inside at
            // r = 6 cm; the hull may leave a few mm more (see the sphere above).
            assert!(gap < 0.005, "link {}: bounds differ by {gap} m", p.name);
        }
    }
}

/// The mesh robot plans the one-object scene, the plan checks, and both engines play it to
/// the goal.
#[test]
fn a_mesh_robot_plans() {
    let scratch = common::Scratch::new("test-mesh-robot");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scene = std::fs::read_to_string(root.join("scenes/herb_single_object.yaml"))
        .unwrap()
        .replace(
            "urdf: ../robots/wam7.urdf",
            &format!("urdf: {}", root.join("robots/wam7_mesh.urdf").display()),
        );
    assert!(scene.contains("wam7_mesh.urdf"));
    let scene_path = scratch.join("mesh_robot.yaml");
    std::fs::write(&scene_path, scene).unwrap();
    let plan = scratch.join("plan.json");
    common::plan_solved(scene_path.to_str().unwrap(), &plan, &[]);
    let (code, stdout, stderr) =
        common::pushplan_in(scratch.path(), &["check", plan.to_str().unwrap()]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    // MuJoCo takes the links' hulls as meshes (placed back from the centroid frame it
    // moves them to) and plays the plan to the goal as rapier does.
    for engine in ["rapier", "mujoco"] {
        let (code, stdout, stderr) = common::pushplan_in(
            scratch.path(),
            &[
                "execute",
                plan.to_str().unwrap(),
                "--trials",
                "1",
                "--engine",
                engine,
            ],
        );
        assert_eq!(code, 0, "{engine}: {stdout}{stderr}");
        assert!(stdout.contains("1 reach the goal"), "{engine}: {stdout}");
    }
}

/// The simplification measures again only the vertices whose earlier distance could still
/// make them the furthest; the eager greedy choice, every exact hull vertex measured from
/// the kept hull in every round (the lowest index of equals), must keep the same
/// vertices in the same order: on a sphere (many vertices exactly as far) and on a
/// lumpy cloud.
#[test]
fn simplifying_lazily_keeps_what_measuring_every_vertex_keeps() {
    use parry3d_f64::query::PointQuery;
    use parry3d_f64::shape::ConvexPolyhedron;
    let mut state = 0x9E37_79B9_7F4A_7C15_u64;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let lumpy: Vec<Point3<f64>> = (0..3000)
        .map(|_| {
            let (u, v, r) = (uniform(), uniform(), 0.05 + 0.01 * uniform());
            let (polar, a) = ((1.0 - 2.0 * u).acos(), 2.0 * std::f64::consts::PI * v);
            Point3::new(
                1.5 * r * polar.sin() * a.cos(),
                r * polar.sin() * a.sin(),
                0.7 * r * polar.cos(),
            )
        })
        .collect();
    for cloud in [fine_sphere(), lumpy] {
        let lazily = simplify_hull(&cloud, HULL_TOLERANCE, MAX_HULL_VERTICES).unwrap();
        let (exact, _) = parry3d_f64::transformation::try_convex_hull(&cloud).unwrap();
        // The start: the same tetrahedron (the simplification stopped at four vertices).
        let mut kept = simplify_hull(&cloud, HULL_TOLERANCE, 4).unwrap().points;
        loop {
            let hull = ConvexPolyhedron::from_convex_hull(&kept).unwrap();
            let (mut worst, mut error) = (0, 0.0);
            for (i, p) in exact.iter().enumerate() {
                let d = hull.distance_to_local_point(p, true);
                if d > error {
                    (worst, error) = (i, d);
                }
            }
            if error <= HULL_TOLERANCE || kept.len() >= MAX_HULL_VERTICES {
                break;
            }
            kept.push(exact[worst]);
        }
        assert!(kept.len() > 20, "{}", kept.len());
        assert_eq!(lazily.points, kept);
    }
}
