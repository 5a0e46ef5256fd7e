// ompl::tools::Benchmark for one run of one planner on one scene (a cell of `pushplan
// bench`), with pushplan's own run properties (the run's index, objects moved, object
// displacement, manipulator path length before and after shortcutting, steps per second).

#include "pushplan/cpp/api/benchmark.h"

#include "pushplan/cpp/planners/darrt/darrt.h"
#include "pushplan/cpp/search/fallback.h"
#include "pushplan/cpp/search/parallel_kpiece.h"
#include "pushplan/cpp/api/planner_source.h"
#include "pushplan/cpp/api/search_builder.h"
#include "pushplan/cpp/problem/problem.h"
#include "pushplan/cpp/search/restarts.h"
#include "pushplan/cpp/search/wrapped_search.h"
#include "pushplan/pushplan.h"
#include "pushplan/src/bridge.rs.h"
#include "pushplan/src/bridge/entry.rs.h"

#include <ompl/control/PathControl.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace pushplan::bridge
{
    /// Why the run's propagations stopped, as run properties (`benches/stops.sh` sums them
    /// per scene class): counts, one column per reason seen.
    static void recordSearch(const SearchStats &stats, ompl::tools::Benchmark::RunProperties &props)
    {
        props["propagations INTEGER"] = std::to_string(stats.propagations);
        props["propagation steps INTEGER"] = std::to_string(stats.steps);
        props["propagations moving the goal object INTEGER"] = std::to_string(stats.moved_goal_object);
        props["propagations moving other objects INTEGER"] = std::to_string(stats.moved_clutter);
        for (std::size_t i = 0; i < stats.stop_reasons.size(); ++i)
        {
            std::string reason(stats.stop_reasons[i]);
            std::replace(reason.begin(), reason.end(), '-', ' ');  // a database column name
            props["stopped by " + reason + " INTEGER"] = std::to_string(stats.stop_counts[i]);
        }
    }

    void benchmark_scene(rust::Str scene_path, const detail::RunSettings &settings, std::uint32_t run, rust::Str log)
    {
        // One run per process, seeded from the grid's seed and the run's index only: the
        // run is the same whichever shard or machine runs it. OMPL's global generator is
        // seeded before any other exists (its planners draw their own seeds from it).
        const std::uint_fast32_t seed = detail::subSeed(settings.seed, 100 + run);
        ompl::RNG::setSeed(seed);
        ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
        // As `plan --threads`: the planners that share one search propagate on lanes of
        // their own models (detail::ParallelKPIECE); the others run on one thread.
        const unsigned threads = detail::checked("threads", settings.threads, settings.threads >= 1 && settings.threads <= 256);
        if (threads > 1 && !planner_shares_one_search(settings.planner))
            throw Error("threads: " + std::string(planner_name(settings.planner)) +
                        " runs one search per thread, which a benchmark's run does not; only push_kpiece "
                        "and kpiece run on several threads there");
        detail::SearchBuilder builder(
            [&] { return detail::asPushplanError([&] { return Problem::load(scene_path); }); });
        const SceneInfo &info = builder.info();
        detail::BuiltSearch built = builder.search(settings, seed, threads > 1 ? detail::lanesFor(threads) : 0);
        const detail::Problem &problem = built.problem;
        const detail::ModelHandlePtr &model = built.models[0];
        const std::vector<detail::ModelHandlePtr> &models = built.models;

        ompl::tools::Benchmark benchmark(*problem.setup, std::string(info.name));
        benchmark.addExperimentParameter("objects", "INTEGER", std::to_string(info.objects));
        benchmark.addExperimentParameter("k", "INTEGER", std::to_string(settings.k));
        // As in Planner::solve: no propagation past the run's time limit, while it runs
        // (not PDST's).
        ob::PlannerPtr planner = built.planner;
        if (planner_cut_at_time_limit(settings.planner))
            planner = std::make_shared<detail::TimeLimitedSearch>(std::move(planner), models, settings.time_limit);
        benchmark.addPlanner(planner);

        std::uint64_t steps_before = 0;
        benchmark.setPreRunEvent([&](const ob::PlannerPtr &) { steps_before = model->propagationSteps(); });
        benchmark.setPostRunEvent([&](const ob::PlannerPtr &planner, ompl::tools::Benchmark::RunProperties &props) {
            props["run INTEGER"] = std::to_string(run);
            props["threads INTEGER"] = std::to_string(threads);
            props["restarts INTEGER"] = std::to_string(detail::restartsOf(planner));
            props["fell back INTEGER"] = std::to_string(detail::fellBack(planner) ? 1 : 0);
            props["handed back INTEGER"] = std::to_string(detail::handedBack(planner));
            // Only the planners that propagate controls through the model have a rate.
            const double propagated = static_cast<double>(model->propagationSteps() - steps_before);
            const double time = std::stod(props["time REAL"]);
            if (propagated > 0)
            {
                props["propagation steps per second REAL"] = std::to_string(propagated / std::max(time, 1e-9));
                recordSearch(detail::summedSearchStats(models), props);
            }
            const auto &pdef = problem.setup->getProblemDefinition();
            if (!pdef->hasExactSolution())
                return;
            const auto measured = [&](const PathMetrics &m, const std::string &suffix) {
                props["object displacement" + suffix + " REAL"] = std::to_string(m.object_displacement);
                props["manipulator path length" + suffix + " REAL"] = std::to_string(m.joint_length);
                props["end effector path length" + suffix + " REAL"] = std::to_string(m.ee_length);
            };
            // DARRT's paths are primitives, checked when found; shortcutting by
            // re-propagation does not apply to them.
            if (const auto *primitives = dynamic_cast<const detail::PrimitivePath *>(pdef->getSolutionPath().get()))
            {
                const PathMetrics &m = primitives->report().metrics;
                props["objects moved INTEGER"] = std::to_string(m.objects_moved);
                props["links in contact INTEGER"] = std::to_string(m.links_in_contact);
                props["pick places INTEGER"] = std::to_string(primitives->report().pick_places);
                measured(m, "");
                return;
            }
            // Finished the one way (planner::finish): re-simulated, then shortcut in the
            // problem the planner searched (Static RRT's clutter stays put).
            const auto found = model->view()->readPath(*pdef->getSolutionPath()->as<oc::PathControl>());
            const FinishedPath s =
                detail::finish(*Finisher::make(model->problem()), found, true,
                               FinishSettings{settings.shortcut, seed, 0, 0.0, false, 0, -1.0, 0,
                                              std::numeric_limits<double>::infinity(), 1});
            props["objects moved INTEGER"] = std::to_string(s.before.objects_moved);
            props["links in contact INTEGER"] = std::to_string(s.before.links_in_contact);
            measured(s.before, "");
            measured(s.after, " shortcut");
        });

        ompl::tools::Benchmark::Request request(settings.time_limit, 8192.0, 1, 0.5, false, false, false);
        benchmark.benchmark(request);
        if (!benchmark.saveResultsToFile(std::string(log).c_str()))
            throw Error("cannot write " + std::string(log));
    }
}  // namespace pushplan::bridge
