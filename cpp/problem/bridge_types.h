// The C++ twins of Rust types the bridge passes as they are (`#[repr(C)]` in Rust, bound
// with cxx::ExternType in src/bridge.rs): same fields, same order, checked here.
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

    /// How one search runs, every value resolved: Rust's planning::RunSettings, the one
    /// settings type of the CLI, a benchmark cell and (resolved from) Options.
    struct RunSettings
    {
        PlannerKind planner;
        bool intermediate_states;        ///< every propagation step joins the tree
        std::uint32_t k;                 ///< control samples per extension
        std::uint32_t threads;           ///< threads to plan on
        std::uint32_t robust_trials;     ///< perturbed re-simulations a solution must pass (0: none)
        std::uint32_t robust_particles;  ///< perturbed worlds every tree state carries
        double time_limit;               ///< s
        std::uint64_t seed;
        double goal_bias;
        double shortcut;                 ///< shortcutting budget (s of work)
        double robust_rate;              ///< share of re-simulations that must reach the goal
        double robust_shortcut;          ///< shortcutting toward robustness (s of work)
        std::uint64_t restart_steps;     ///< first restart budget (propagation steps; 0: never)
        std::uint64_t fallback_steps;    ///< Push KPIECE's patience (propagation steps; 0: never)
    };
    static_assert(offsetof(RunSettings, intermediate_states) == 1 && offsetof(RunSettings, k) == 4 &&
                      offsetof(RunSettings, robust_particles) == 16 && offsetof(RunSettings, time_limit) == 24 &&
                      offsetof(RunSettings, fallback_steps) == 80 && sizeof(RunSettings) == 88,
                  "RunSettings must have the layout of Rust's #[repr(C)] planning::RunSettings");

    /// Reaching a grasp: Rust's planner::ReachSettings.
    struct ReachSettings
    {
        double time_limit;  ///< s
        std::uint64_t seed;
        double sample_probability;  ///< IK-BiRRT's P_sample
    };
    static_assert(offsetof(ReachSettings, seed) == 8 && offsetof(ReachSettings, sample_probability) == 16 &&
                      sizeof(ReachSettings) == 24,
                  "ReachSettings must have the layout of Rust's #[repr(C)] planner::ReachSettings");

    /// How far a search is: Rust's planner::SearchProgress (pushplan::Progress without its
    /// note, which crosses beside it).
    struct SearchProgress
    {
        double seconds;
        std::uint64_t propagation_steps;
        double steps_per_second;
        double propagating;  ///< share of the time since the last report
        std::size_t tree_states;
        double closest_goal_distance;
        std::uint32_t searches;
    };
    static_assert(offsetof(SearchProgress, tree_states) == 32 && offsetof(SearchProgress, searches) == 48 &&
                      sizeof(SearchProgress) == 56,
                  "SearchProgress must have the layout of Rust's #[repr(C)] planner::SearchProgress");

    /// How a search went: Rust's planner::SearchSummary.
    struct SearchSummary
    {
        bool exact;
        bool approximate;
        double planning_time;  ///< s
        std::size_t tree_size;
        std::uint64_t propagation_steps;
        std::uint64_t restarts;
        std::uint64_t fallbacks;
    };
    static_assert(offsetof(SearchSummary, approximate) == 1 && offsetof(SearchSummary, planning_time) == 8 &&
                      offsetof(SearchSummary, fallbacks) == 40 && sizeof(SearchSummary) == 48,
                  "SearchSummary must have the layout of Rust's #[repr(C)] planner::SearchSummary");
}  // namespace pushplan::detail
