//! MuJoCo as the 3D world of an execution: the second judge, whose contact model differs
//! from rapier's (soft contacts from a convex optimisation per step, objects standing on
//! their own faces and rims rather than on evenly spread feet).
//!
//! The arm's links are free bodies far heavier than the objects ([`mjcf::LINK_MASS`]),
//! held up against gravity by a constant force: before each step the execution sets each
//! link's pose and its velocity towards the next pose, so the link moves exactly along the
//! plan while its contacts see its true velocity (MuJoCo's moving "mocap" bodies have
//! none, which would lose the friction of a link sliding past an object).

mod bridge;
pub mod mjcf;

use super::engine::{Engine, STEP};
use crate::math::Pose2;
use crate::physics::limit_surface::GRAVITY;
use crate::scene::{Scene, Table};
use cxx::UniquePtr;
use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector2, Vector3};

/// The MuJoCo world of one execution.
pub struct MujocoWorld {
    world: UniquePtr<bridge::ffi::MujocoWorld>,
    /// (chain link, body id, pose `X_WL` now) of every solid link.
    links: Vec<(usize, i32, Isometry3<f64>)>,
    /// Whether the links were given their next poses since the last step.
    arm_moved: bool,
    /// Body ids of the objects, scene order.
    objects: Vec<i32>,
    table: Table,
}

impl MujocoWorld {
    /// The scene's table, obstacles and objects (at `objects`, the start poses), and the
    /// arm's links at `link_poses` (`X_WL`, one per chain link).
    pub fn new(
        scene: &Scene,
        objects: &[Pose2],
        link_poses: &[Isometry3<f64>],
    ) -> Result<MujocoWorld, String> {
        let text = mjcf::mjcf(scene, objects, link_poses)?;
        let mut world = bridge::ffi::load(&text).map_err(|e| e.what().to_string())?;
        let id = |world: &bridge::ffi::MujocoWorld, name: &str| match world.body(name) {
            -1 => Err(format!(
                "internal error: the MuJoCo model has no body '{name}'"
            )),
            id => Ok(id),
        };
        let mut links = Vec::new();
        for link in scene.robot.solid_links() {
            let body = id(&world, &mjcf::link_body(link))?;
            // Held up: gravity's pull on the link, cancelled at its centre of mass.
            world
                .pin_mut()
                .set_force(body, &[0.0, 0.0, mjcf::LINK_MASS * GRAVITY])
                .map_err(|e| e.what().to_string())?;
            links.push((link, body, link_poses[link]));
        }
        let objects = (0..scene.objects.len())
            .map(|i| id(&world, &mjcf::object_body(i)))
            .collect::<Result<_, _>>()?;
        Ok(MujocoWorld {
            world,
            links,
            arm_moved: false,
            objects,
            table: scene.table.clone(),
        })
    }

    /// MuJoCo's version, as `2.2.2`.
    pub fn version() -> String {
        let v = bridge::ffi::version();
        format!("{}.{}.{}", v / 100, v / 10 % 10, v % 10)
    }

    /// Sets link `body` at `pose` moving to `next` within one step.
    fn drive(&mut self, body: i32, pose: &Isometry3<f64>, next: &Isometry3<f64>) {
        let v = (next.translation.vector - pose.translation.vector) / STEP;
        // Angular velocity: world frame from the turn between the poses, then into the
        // body frame (MuJoCo's free joints take it there).
        let w_world = (next.rotation * pose.rotation.inverse()).scaled_axis() / STEP;
        let w_body = pose.rotation.inverse() * w_world;
        let t = pose.translation.vector;
        let q = pose.rotation.quaternion();
        self.world
            .pin_mut()
            .set_free_joint(
                body,
                &[t.x, t.y, t.z, q.w, q.i, q.j, q.k],
                &[v.x, v.y, v.z, w_body.x, w_body.y, w_body.z],
            )
            .expect("link bodies have free joints");
    }
}

impl Engine for MujocoWorld {
    fn move_arm(&mut self, link_poses: &[Isometry3<f64>]) {
        for k in 0..self.links.len() {
            let (link, body, pose) = self.links[k];
            self.drive(body, &pose, &link_poses[link]);
            self.links[k].2 = link_poses[link];
        }
        self.arm_moved = true;
    }

    fn step(&mut self) {
        if !self.arm_moved {
            // Not driven this step: the links stay where they are.
            for k in 0..self.links.len() {
                let (_, body, pose) = self.links[k];
                self.drive(body, &pose, &pose);
            }
        }
        self.world.pin_mut().step();
        self.arm_moved = false;
    }

    fn object_pose(&self, i: usize) -> Isometry3<f64> {
        let mut p = [0.0; 7];
        self.world
            .free_joint_pose(self.objects[i], &mut p)
            .expect("object bodies have free joints");
        Isometry3::from_parts(
            Translation3::new(p[0], p[1], p[2]),
            UnitQuaternion::from_quaternion(Quaternion::new(p[3], p[4], p[5], p[6])),
        )
    }

    /// Its centre has left the table (the table top is an unbounded plane here, so an
    /// object past the edge does not fall by itself).
    fn object_fell_off(&self, i: usize) -> bool {
        let t = self.object_pose(i).translation;
        !self.table.contains(Vector2::new(t.x, t.y))
    }

    fn set_object_velocity(&mut self, i: usize, v: Vector3<f64>) {
        let pose = self.object_pose(i);
        let t = pose.translation.vector;
        let q = pose.rotation.quaternion();
        self.world
            .pin_mut()
            .set_free_joint(
                self.objects[i],
                &[t.x, t.y, t.z, q.w, q.i, q.j, q.k],
                &[v.x, v.y, v.z, 0.0, 0.0, 0.0],
            )
            .expect("object bodies have free joints");
    }

    fn object_velocity(&self, i: usize) -> Vector3<f64> {
        let mut v = [0.0; 6];
        self.world
            .free_joint_velocity(self.objects[i], &mut v)
            .expect("object bodies have free joints");
        Vector3::new(v[0], v[1], v[2])
    }

    fn touching_objects(&self) -> Option<(usize, usize)> {
        let mut pair = [0; 2];
        let touching = self
            .world
            .touching(&self.objects, &mut pair)
            .expect("a pair has two bodies");
        let object = |body: i32| self.objects.iter().position(|&b| b == body);
        match (touching, object(pair[0]), object(pair[1])) {
            (true, Some(a), Some(b)) => Some((a.min(b), a.max(b))),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DVector;
    use std::path::Path;

    /// A driven link ends each step where it was sent, however it is turned: the
    /// velocities handed to MuJoCo follow its free-joint convention (linear in the world
    /// frame, angular in the body's).
    #[test]
    fn a_driven_link_ends_the_step_where_it_was_sent() {
        // A hand turned 0.7 rad about z, so that the body and world frames differ.
        let yaml = "robot: {type: planar_hand, shape: {type: box, size: [0.04, 0.12, 0.01]}, \
                    start: [0.4, 0.0, 0.7], height: 0.05}
table: {height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}
objects:
  - {name: box, shape: {type: box, size: [0.1, 0.1, 0.1]}, pose: [0.8, 0.0, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}
goal: {object: box, center: [0.9, 0.3], radius: 0.1}
";
        let scene = Scene::from_yaml(yaml, Path::new("mujoco-link-test.yaml")).unwrap();
        let mut poses = Vec::new();
        let q = DVector::from_vec(vec![0.4, 0.0, 0.7]);
        scene.robot.chain.forward_kinematics(&q, &mut poses);
        let mut world = MujocoWorld::new(&scene, &scene.start.objects, &poses).unwrap();
        let (link, body, pose) = world.links[world.links.len() - 1];
        // A turn of 0.5 mrad about a slanted world axis and a 0.3 mm move in one step:
        // 0.5 rad/s and 0.3 m/s.
        let turn = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.2, 0.4) * 1e-3);
        let next = Isometry3::from_parts(
            Translation3::from(pose.translation.vector + Vector3::new(2e-4, -1e-4, 2e-4)),
            turn * pose.rotation,
        );
        let mut target = poses.clone();
        target[link] = next;
        world.move_arm(&target);
        world.step();
        let mut p = [0.0; 7];
        world.world.free_joint_pose(body, &mut p).unwrap();
        let reached = Isometry3::from_parts(
            Translation3::new(p[0], p[1], p[2]),
            UnitQuaternion::from_quaternion(Quaternion::new(p[3], p[4], p[5], p[6])),
        );
        let moved = (reached.translation.vector - next.translation.vector).norm();
        let turned = reached.rotation.angle_to(&next.rotation);
        assert!(moved < 1e-6 && turned < 1e-6, "{moved} m, {turned} rad off");
    }
}
