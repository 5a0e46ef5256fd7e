// MuJoCo as a second 3D engine for execution checks: one model compiled from MJCF text
// (written by the Rust side, `src/planning/execute/mujoco/mjcf.rs`) and its data. The arm's
// links and the objects are free bodies; the Rust side prescribes the links' poses and
// velocities before each step and reads the objects' poses after it.
#pragma once

#include "rust/cxx.h"

#include <cstddef>
#include <cstdint>
#include <memory>

struct mjModel_;
struct mjData_;

namespace pushplan::mujoco
{
    class MujocoWorld
    {
    public:
        MujocoWorld(mjModel_ *model, mjData_ *data);
        ~MujocoWorld();
        MujocoWorld(const MujocoWorld &) = delete;
        MujocoWorld &operator=(const MujocoWorld &) = delete;

        /// The body's id, or -1 when the model has no body of that name.
        int body(rust::Str name) const;
        /// Sets the free joint of `body`: position and quaternion (w, x, y, z) of its frame
        /// in the world, linear velocity of its origin in the world frame and angular
        /// velocity in the body's own frame (MuJoCo's free-joint convention).
        void setFreeJoint(int body, rust::Slice<const double> pose,
                          rust::Slice<const double> velocity);
        /// Position and quaternion (w, x, y, z) of `body`'s free joint: its frame in the
        /// world now (not the pose the last step's kinematics started from).
        void freeJointPose(int body, rust::Slice<double> pose) const;
        /// Velocity of `body`'s free joint: linear (world frame), angular (body frame).
        void freeJointVelocity(int body, rust::Slice<double> velocity) const;
        /// A force (N, world frame) applied at `body`'s centre of mass in every step.
        void setForce(int body, rust::Slice<const double> force);
        /// One step of the model's time step.
        void step();
        /// The first contact of the last step in which the geoms of two of `bodies`
        /// penetrate: their body ids in `pair`; false when there is none.
        bool touching(rust::Slice<const std::int32_t> bodies, rust::Slice<std::int32_t> pair) const;

    private:
        int freeJointAddress(int body, bool velocity) const;
        mjModel_ *model_;
        mjData_ *data_;
    };

    /// Compiles MJCF text; throws with MuJoCo's message when it does not compile.
    std::unique_ptr<MujocoWorld> load(rust::Str mjcf);
    /// MuJoCo's version (e.g. 222).
    int version();
}  // namespace pushplan::mujoco
