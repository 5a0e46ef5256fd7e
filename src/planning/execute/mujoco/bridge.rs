//! The declarations cxx generates MuJoCo's side from (`cpp/engines/mujoco_world.h`).

#[allow(missing_docs)]
#[cxx::bridge(namespace = "pushplan::mujoco")]
pub mod ffi {
    unsafe extern "C++" {
        include!("pushplan/cpp/engines/mujoco_world.h");
        type MujocoWorld;
        /// Compiles MJCF text (MuJoCo's message when it does not compile).
        fn load(mjcf: &str) -> Result<UniquePtr<MujocoWorld>>;
        /// MuJoCo's version (222 for 2.2.2).
        fn version() -> i32;
        fn body(self: &MujocoWorld, name: &str) -> i32;
        #[cxx_name = "setFreeJoint"]
        fn set_free_joint(
            self: Pin<&mut MujocoWorld>,
            body: i32,
            pose: &[f64],
            velocity: &[f64],
        ) -> Result<()>;
        #[cxx_name = "freeJointPose"]
        fn free_joint_pose(self: &MujocoWorld, body: i32, pose: &mut [f64]) -> Result<()>;
        #[cxx_name = "freeJointVelocity"]
        fn free_joint_velocity(self: &MujocoWorld, body: i32, velocity: &mut [f64]) -> Result<()>;
        #[cxx_name = "setForce"]
        fn set_force(self: Pin<&mut MujocoWorld>, body: i32, force: &[f64]) -> Result<()>;
        fn step(self: Pin<&mut MujocoWorld>);
        fn touching(self: &MujocoWorld, bodies: &[i32], pair: &mut [i32]) -> Result<bool>;
    }
}
