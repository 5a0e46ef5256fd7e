#include "pushplan/cpp/api/solve.h"

#include "pushplan/cpp/api/planner_source.h"
#include "pushplan/pushplan.h"
#include "pushplan/src/bridge/entry.rs.h"

namespace pushplan::bridge
{
    SolveOutput solve(const Problem &problem, const detail::RunSettings &settings, bool report,
                      rust::Fn<void(const detail::SearchProgress &, rust::Str)> progress)
    {
        // The caller finishes the path itself (planning::finish), to report on it.
        detail::RunSettings run = settings;
        run.shortcut = 0.0;
        std::function<void(const Progress &)> tell;
        if (report)
            tell = [progress](const Progress &p) {
                progress(detail::SearchProgress{p.seconds, p.propagation_steps, p.steps_per_second, p.propagating,
                                                p.tree_states.value_or(0), p.closest_goal_distance, p.searches},
                         p.note);
            };
        const Plan plan = detail::solve(
            [&] { return problem.duplicate(); }, [&](const SceneInfo &) { return run; }, tell, detail::Finishing::AsFound);
        SolveOutput out;
        out.summary = detail::SearchSummary{plan.solved,          !plan.solved && !plan.controls.empty(),
                                            plan.planning_time,   plan.tree_size,
                                            plan.propagation_steps, plan.restarts,
                                            plan.fallbacks,       plan.handed_back,
                                            plan.lanes};
        out.robustness = plan.robustness;
        out.robustness_trials = plan.robustness_trials;
        out.search.propagations = plan.search.propagations;
        out.search.steps = plan.search.steps;
        out.search.moved_goal_object = plan.search.moved_goal_object;
        out.search.moved_clutter = plan.search.moved_clutter;
        for (const auto &[reason, count] : plan.search.stopped)
        {
            out.search.stop_reasons.emplace_back(reason);
            out.search.stop_counts.push_back(count);
        }
        for (const auto &[a, b, count] : plan.search.self_collisions)
        {
            out.search.self_collision_links.emplace_back(a);
            out.search.self_collision_links.emplace_back(b);
            out.search.self_collision_counts.push_back(count);
        }
        out.dof = plan.joint_names.size();
        out.objects = plan.object_names.size();
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

    ReachOutput reach(const Problem &problem, rust::Str object, rust::Slice<const double> from,
                      const detail::ReachSettings &settings)
    {
        std::size_t dof = 0;
        const Reach r = detail::reach(
            [&] { return problem.duplicate(); }, std::string(object),
            [&](const SceneInfo &info) {
                dof = info.dof;
                return settings;
            },
            [&](const SceneInfo &info) {
                if (from.empty())
                    return std::vector<double>(info.start.begin(), info.start.end());
                if (from.size() != detail::FlatLayout{info.dof, info.objects}.size())
                    throw Error("reach: the state to reach from is not of this scene");
                return std::vector<double>(from.begin(), from.end());
            });
        ReachOutput out;
        out.solved = r.solved;
        out.planning_time = r.planning_time;
        out.goal_samples = r.goal_samples;
        out.tree_size = r.tree_size;
        out.dof = dof;
        for (const auto &q : r.waypoints)
            for (Eigen::Index i = 0; i < q.size(); ++i)
                out.waypoints.push_back(q[i]);
        return out;
    }
}  // namespace pushplan::bridge
