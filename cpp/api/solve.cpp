#include "pushplan/cpp/api/solve.h"

#include "pushplan/pushplan.h"
#include "pushplan/src/bridge/entry.rs.h"

namespace pushplan::bridge
{
    SolveOutput solve(rust::Str scene_path, const SolveOptions &options,
                      rust::Fn<void(const SearchProgress &)> progress)
    {
        Options o;
        o.planner = options.planner;
        o.time_limit = options.time_limit;
        o.seed = options.seed;
        o.k = options.k;
        o.goal_bias = options.goal_bias;
        o.intermediate_states = options.intermediate_states;
        o.progress = options.progress;
        if (options.progress)
            o.on_progress = [progress](const Progress &p) {
                SearchProgress report;
                report.seconds = p.seconds;
                report.propagation_steps = p.propagation_steps;
                report.steps_per_second = p.steps_per_second;
                report.propagating = p.propagating;
                report.tree_states = p.tree_states.value_or(0);
                report.searches = p.searches;
                report.closest_goal_distance = p.closest_goal_distance;
                report.note = p.note;
                progress(report);
            };
        o.robust_trials = static_cast<unsigned>(options.robust_trials);
        o.robust_rate = options.robust_rate;
        o.robust_shortcut = options.robust_shortcut;
        o.robust_particles = options.robust_particles;
        o.threads = options.threads;
        o.restart_steps = options.restart_steps;
        o.fallback_steps = options.fallback_steps;
        o.shortcut = 0.0;  // the CLI finishes the path itself (planner::finish), to report on it

        const Plan plan = Planner(std::string(scene_path)).solve(o);
        SolveOutput out;
        out.exact = plan.solved;
        out.approximate = !plan.solved && !plan.controls.empty();
        out.planning_time = plan.planning_time;
        out.tree_size = plan.tree_size;
        out.propagation_steps = plan.propagation_steps;
        out.restarts = plan.restarts;
        out.fallbacks = plan.fallbacks;
        out.search.propagations = plan.search.propagations;
        out.search.steps = plan.search.steps;
        out.search.moved_goal_object = plan.search.moved_goal_object;
        out.search.moved_clutter = plan.search.moved_clutter;
        for (const auto &[reason, count] : plan.search.stopped)
        {
            out.search.stop_reasons.emplace_back(reason);
            out.search.stop_counts.push_back(count);
        }
        for (std::size_t i = 0; i < plan.joint_trajectory.size(); ++i)
        {
            for (double v : plan.joint_trajectory[i])
                out.states.push_back(v);
            for (const auto &p : plan.object_poses[i])
                for (double v : p)
                    out.states.push_back(v);
        }
        for (const auto &c : plan.controls)
        {
            for (double v : c.ee_velocity)
                out.controls.push_back(v);
            for (double v : c.nullspace)
                out.controls.push_back(v);
            out.steps.push_back(c.steps);
        }
        return out;
    }

    ReachOutput reach(rust::Str scene_path, rust::Str object, rust::Slice<const double> from_q,
                      rust::Slice<const double> from_objects, const ReachOptions &options)
    {
        const Planner planner{std::string(scene_path)};
        pushplan::ReachOptions o;
        o.time_limit = options.time_limit;
        o.seed = options.seed;
        o.sample_probability = options.sample_probability;
        // A state to reach from is passed as the one state of a plan.
        Plan after;
        after.joint_trajectory.emplace_back(Eigen::Map<const Eigen::VectorXd>(from_q.data(), from_q.size()));
        after.object_poses.emplace_back();
        for (std::size_t at = 0; at + 3 <= from_objects.size(); at += 3)
            after.object_poses.back().emplace_back(from_objects[at], from_objects[at + 1], from_objects[at + 2]);
        const Reach r = planner.reach(std::string(object), o, from_q.empty() ? nullptr : &after);
        ReachOutput out;
        out.solved = r.solved;
        out.planning_time = r.planning_time;
        out.goal_samples = r.goal_samples;
        out.tree_size = r.tree_size;
        for (const auto &q : r.waypoints)
            for (Eigen::Index i = 0; i < q.size(); ++i)
                out.waypoints.push_back(q[i]);
        return out;
    }
}  // namespace pushplan::bridge
