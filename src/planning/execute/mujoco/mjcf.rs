//! The MJCF text of a scene's execution world.
//!
//! Frames: world `W` with z up, as the scene's. The table top is a plane at its height
//! (MuJoCo's plane-box and plane-cylinder collisions give several contacts, so an object
//! stands on its own corners and rim; its general convex collision gives one). Every
//! solid link is a free body of its own, driven by the execution; every object is a free
//! body whose frame is its planar frame lifted onto the table top.
//!
//! Friction is per pair, as in the planning model: object–table and object–obstacle
//! `mu_g`, object–arm `mu_c`, object–object the mean of the two `mu_c`. Only these pairs
//! collide (`<contact><pair>`); every other geom has no contact type. Friction cones are
//! elliptic: with MuJoCo's default pyramidal cones a hand sliding at 45 degrees along a
//! box's face dragged it sideways by the same 4-5 cm whether `mu_c` was 0.3 or 0.8, where
//! Coulomb's law has 3 and 8 (`tests/integration/execute.rs`). Everything else is
//! MuJoCo's default contact model (soft contacts, `solref` 0.02 s, `solimp` 0.9-0.95).

use super::super::engine::STEP;
use crate::math::Pose2;
use crate::physics::limit_surface::GRAVITY;
use crate::scene::Scene;
use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use parry3d_f64::shape::SharedShape;
use std::f64::consts::FRAC_PI_2;
use std::fmt::Write;

/// Mass of each arm link body (kg): far heavier than any object, so that a contact barely
/// changes the velocity the execution gives the link within a step.
pub const LINK_MASS: f64 = 1000.0;
/// Principal moments of inertia of each arm link body (kg m^2; a 0.3 m radius of gyration).
const LINK_INERTIA: f64 = 100.0;

/// The body names the world reads back: arm links `link{k}` (chain link `k`), objects
/// `object{i}` (scene order).
pub fn link_body(link: usize) -> String {
    format!("link{link}")
}

/// See [`link_body`].
pub fn object_body(object: usize) -> String {
    format!("object{object}")
}

/// The MJCF text of `scene` with its objects at `objects` and the arm's links at
/// `link_poses` (`X_WL`, one per chain link). Fails for a shape MJCF has no geom for.
pub fn mjcf(
    scene: &Scene,
    objects: &[Pose2],
    link_poses: &[Isometry3<f64>],
) -> Result<String, String> {
    let mut assets = String::new();
    let mut bodies = String::new();
    let table = &scene.table;
    let (cx, cy) = ((table.x.0 + table.x.1) / 2.0, (table.y.0 + table.y.1) / 2.0);
    let (hx, hy) = ((table.x.1 - table.x.0) / 2.0, (table.y.1 - table.y.0) / 2.0);
    writeln!(
        bodies,
        r#"    <geom name="table" type="plane" pos="{cx} {cy} {}" size="{hx} {hy} 0.01"/>"#,
        table.top
    )
    .unwrap();
    let mut obstacle_geoms = Vec::new();
    for (k, obstacle) in scene.obstacles.iter().enumerate() {
        let name = format!("obstacle{k}");
        let pose = obstacle.geometry.world_pose(&obstacle.pose);
        bodies += &geom(&name, &obstacle.geometry.shape, &pose, &mut assets, "")
            .map_err(|e| format!("obstacle '{}': {e}", obstacle.name))?;
        obstacle_geoms.push(name);
    }
    let mut link_geoms = Vec::new();
    for link in scene.robot.solid_links() {
        let pose = &link_poses[link];
        writeln!(
            bodies,
            r#"    <body name="{}" {}>
      <freejoint/>
      <inertial pos="0 0 0" mass="{LINK_MASS}" diaginertia="{LINK_INERTIA} {LINK_INERTIA} {LINK_INERTIA}"/>"#,
            link_body(link),
            placement(pose)
        )
        .unwrap();
        for (j, g) in scene.robot.chain.links[link].geometry.iter().enumerate() {
            let name = format!("link{link}_{j}");
            bodies += &geom(&name, &g.shape, &g.local, &mut assets, "  ")
                .map_err(|e| format!("link '{}': {e}", scene.robot.chain.links[link].name))?;
            link_geoms.push(name);
        }
        bodies += "    </body>\n";
    }
    for (i, (object, pose)) in scene.objects.iter().zip(objects).enumerate() {
        writeln!(
            bodies,
            r#"    <body name="{}" {}>
      <freejoint/>"#,
            object_body(i),
            placement(&pose.to_isometry(table.top))
        )
        .unwrap();
        let mass = format!(r#" mass="{}""#, object.mass);
        let g = geom(
            &object_body(i),
            &object.geometry.shape,
            &object.geometry.local,
            &mut assets,
            "  ",
        )
        .map_err(|e| format!("object '{}': {e}", object.name))?;
        bodies += &g.replacen("/>", &format!("{mass}/>"), 1);
        bodies += "    </body>\n";
    }

    let mut pairs = String::new();
    let mut pair = |a: &str, b: &str, mu: f64| {
        writeln!(
            pairs,
            r#"    <pair geom1="{a}" geom2="{b}" condim="3" friction="{mu} {mu} 0.005 0.0001 0.0001"/>"#
        )
        .unwrap()
    };
    for (i, object) in scene.objects.iter().enumerate() {
        let name = object_body(i);
        pair(&name, "table", object.mu_g);
        for obstacle in &obstacle_geoms {
            pair(&name, obstacle, object.mu_g);
        }
        for link in &link_geoms {
            pair(&name, link, object.mu_c);
        }
        for (j, other) in scene.objects.iter().enumerate().skip(i + 1) {
            pair(&name, &object_body(j), 0.5 * (object.mu_c + other.mu_c));
        }
    }
    Ok(format!(
        r#"<mujoco model="pushplan">
  <compiler angle="radian"/>
  <option timestep="{STEP}" gravity="0 0 {}" cone="elliptic"/>
  <default>
    <geom contype="0" conaffinity="0"/>
  </default>
  <asset>
{assets}  </asset>
  <worldbody>
{bodies}  </worldbody>
  <contact>
{pairs}  </contact>
</mujoco>
"#,
        -GRAVITY
    ))
}

/// `pos` and `quat` (w x y z) attributes of a pose.
fn placement(pose: &Isometry3<f64>) -> String {
    let t = pose.translation.vector;
    let q = pose.rotation.quaternion();
    format!(
        r#"pos="{} {} {}" quat="{} {} {} {}""#,
        t.x, t.y, t.z, q.w, q.i, q.j, q.k
    )
}

/// The `<geom>` element of `shape` placed at `local` in its body (the world for a static
/// geom), with `extra` attributes; a hull's vertices go into a mesh asset, already placed
/// in the body frame.
fn geom(
    name: &str,
    shape: &SharedShape,
    local: &Isometry3<f64>,
    assets: &mut String,
    extra: &str,
) -> Result<String, String> {
    let element = if let Some(cuboid) = shape.as_cuboid() {
        let h = cuboid.half_extents;
        format!(
            r#"type="box" size="{} {} {}" {}"#,
            h.x,
            h.y,
            h.z,
            placement(local)
        )
    } else if let Some(ball) = shape.as_ball() {
        format!(
            r#"type="sphere" size="{}" {}"#,
            ball.radius,
            placement(local)
        )
    } else if let Some(cylinder) = shape.as_cylinder() {
        // parry's cylinder runs along its y axis, MuJoCo's along z: Rx(-pi/2) takes z to y.
        let y_from_z = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), -FRAC_PI_2);
        let frame = Isometry3::from_parts(local.translation, local.rotation * y_from_z);
        format!(
            r#"type="cylinder" size="{} {}" {}"#,
            cylinder.radius,
            cylinder.half_height,
            placement(&frame)
        )
    } else if let Some(capsule) = shape.as_capsule() {
        let (a, b) = (local * capsule.segment.a, local * capsule.segment.b);
        format!(
            r#"type="capsule" size="{}" fromto="{} {} {} {} {} {}""#,
            capsule.radius, a.x, a.y, a.z, b.x, b.y, b.z
        )
    } else if let Some(hull) = shape.as_convex_polyhedron() {
        let vertices: Vec<String> = hull
            .points()
            .iter()
            .map(|p| {
                let p = local * p;
                format!("{} {} {}", p.x, p.y, p.z)
            })
            .collect();
        writeln!(
            assets,
            r#"    <mesh name="{name}" vertex="{}"/>"#,
            vertices.join(" ")
        )
        .unwrap();
        format!(r#"type="mesh" mesh="{name}""#)
    } else {
        return Err(format!("MuJoCo has no geom for a {:?}", shape.shape_type()));
    };
    Ok(format!(r#"      <geom name="{name}" {element} {extra}/>"#) + "\n")
}
