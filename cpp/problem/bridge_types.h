// The C++ twins of Rust types the bridge passes as they are (`#[repr(C)]` in Rust, bound
// with cxx::ExternType in src/ffi.rs): same fields, same order, checked here.
#pragma once

#include "pushplan/pushplan.h"

#include <cstddef>
#include <cstdint>

namespace pushplan
{
    // Rust's path::PathMetrics.
    static_assert(offsetof(PathMetrics, objects_moved) == 24 && offsetof(PathMetrics, duration) == 40 &&
                      sizeof(PathMetrics) == 48,
                  "PathMetrics must have the layout of Rust's #[repr(C)] path::PathMetrics");
}  // namespace pushplan

namespace pushplan::detail
{
    /// The scene's planner parameters: Rust's scene::PlannerSpec.
    struct PlannerParams
    {
        double time_limit;           ///< search time limit (s)
        std::uint64_t seed;          ///< random seed
        std::uint32_t k;             ///< control samples per extension
        std::uint32_t nearest_checks;  ///< states a nearest-neighbour query compares (0: all it must)
        double goal_bias;            ///< probability of sampling the goal
        double step;                 ///< propagation step (s)
        double min_duration;         ///< shortest control (s)
        double max_duration;         ///< longest control (s)
        double max_ee_speed;         ///< bound on |vx|, |vy| (m/s)
        double max_ee_turn_rate;     ///< bound on |omega_z| (rad/s)
        double max_nullspace_speed;  ///< bound on each null-space sample (rad/s)
        double robot_weight;         ///< distance weights
        double object_weight;
        double goal_object_weight;
        double rotation_length;  ///< m per radian of object yaw in the distance
    };
    static_assert(offsetof(PlannerParams, k) == 16 && offsetof(PlannerParams, nearest_checks) == 20 && offsetof(PlannerParams, goal_bias) == 24 &&
                      offsetof(PlannerParams, rotation_length) == 104 && sizeof(PlannerParams) == 112,
                  "PlannerParams must have the layout of Rust's #[repr(C)] scene::PlannerSpec");
}  // namespace pushplan::detail
