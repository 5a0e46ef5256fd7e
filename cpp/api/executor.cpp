// pushplan::Executor: closed-loop execution for an application that observes its own
// world. The decisions are the model's (Rust's planner::closed_loop::Executor, the one
// `execute --closed-loop` runs), its re-plans searched here by OMPL.

#include "pushplan/pushplan.h"

#include "pushplan/cpp/api/planner_source.h"

#include <utility>

namespace pushplan
{
    struct Executor::State
    {
        rust::Box<bridge::Executor> executor;
        /// The scene's sizes and names, observations are read in.
        bridge::SceneInfo info;
    };

    Executor::Executor(const Planner &planner, const Plan &plan, const ExecutorOptions &options)
    {
        state_ = detail::asPushplanError([&] {
            if (!plan.solved)
                throw Error("Executor: the plan is not solved (Plan::solved is false): there is nothing to play");
            if (plan.joint_trajectory.empty() || plan.object_poses.empty())
                throw Error("Executor: the plan has no states (Plan::joint_trajectory is empty)");
            // From the plan's first state: the scene's start, or where a re-plan began.
            const Observation start{plan.joint_trajectory.front(), plan.object_poses.front()};
            const rust::Box<bridge::Problem> problem = detail::startingAt(planner.source().load(), start);
            bridge::SceneInfo info = problem->info();
            bridge::ExecutorSettings settings = bridge::executor_defaults();
            settings.planner = detail::checkedKind(options.planner);
            if (!bridge::planner_yields_controls(settings.planner))
                throw Error("ExecutorOptions::planner: " + std::string(bridge::planner_name(settings.planner)) +
                            " yields no controls to re-plan with");
            settings.seed = options.seed.value_or(bridge::run_settings_of_scene(settings.planner, info.planner).seed);
            settings.replan_threads = options.replan_threads.value_or(detail::defaultThreads());
            settings.replan_time = options.replan_time.value_or(settings.replan_time);
            settings.replan_shortcut = options.replan_shortcut.value_or(settings.replan_shortcut);
            settings.replan_polish = options.replan_polish.value_or(settings.replan_polish);
            settings.replan_mend = options.replan_mend.value_or(settings.replan_mend);
            settings.max_replans = options.max_replans.value_or(settings.max_replans);
            settings.replan_budget = options.replan_budget.value_or(settings.replan_budget);
            settings.replan_leg = options.replan_leg.value_or(settings.replan_leg);
            settings.repair_ahead = options.repair_ahead.value_or(settings.repair_ahead);
            settings.speed = options.speed.value_or(settings.speed);
            detail::FlatPath path;
            detail::appendControls(path, plan, 0, plan.controls.size());
            rust::Box<bridge::Executor> executor =
                bridge::Executor::make(*problem, detail::slice(path.controls), detail::slice(path.steps), settings);
            return std::make_unique<State>(State{std::move(executor), std::move(info)});
        });
    }

    Executor::~Executor() = default;
    Executor::Executor(Executor &&) noexcept = default;
    Executor &Executor::operator=(Executor &&) noexcept = default;

    ExecutorStep Executor::step(const Observation &observed)
    {
        return detail::asPushplanError([&] {
            if (!state_)
                throw Error("this pushplan::Executor was moved from: it has no plan");
            const bridge::SceneInfo &info = state_->info;
            const std::vector<double> flat = detail::flatObservation(observed, info);
            const bridge::ExecutorStep step = state_->executor->step(detail::slice(flat));
            ExecutorStep out;
            out.why = std::string(step.why);
            switch (step.kind)
            {
            case bridge::ExecutorStepKind::Play:
                out.kind = ExecutorStep::Kind::Play;
                out.control = detail::controlAt(step.control.data(), step.steps, info);
                out.trajectory = detail::trajectoryOf(step.trajectory, info);
                out.predicted = detail::observationAt(step.predicted, 0, info);
                break;
            case bridge::ExecutorStepKind::Finished:
                out.kind = ExecutorStep::Kind::Finished;
                break;
            default:
                out.kind = ExecutorStep::Kind::Stopped;
                break;
            }
            return out;
        });
    }

    ExecutorReport Executor::report() const
    {
        if (!state_)
            throw Error("this pushplan::Executor was moved from: it has no plan");
        const bridge::ExecutorReport r = state_->executor->report();
        ExecutorReport out;
        out.controls_played = r.controls_played;
        out.kept = r.kept;
        out.invalid_rests = r.invalid_rests;
        out.replans = r.replans;
        out.repairs = r.repairs;
        out.failed_replans = r.failed_replans;
        out.legs = r.legs;
        out.backoffs = r.backoffs;
        out.search_time = r.search_time;
        out.latencies.assign(r.latencies.begin(), r.latencies.end());
        out.replan_latencies.assign(r.replan_latencies.begin(), r.replan_latencies.end());
        out.last_failure = std::string(r.last_failure);
        out.stopped = std::string(r.stopped);
        return out;
    }
}  // namespace pushplan
