// What the C++ tests of the search internals share: a search set up on a scene the way
// Planner::solve sets one up (its model, problem, lanes and planner) and run until a
// budget of propagation steps, so that what it finds does not depend on timing.
#pragma once

#include "pushplan/cpp/problem/problem.h"

#include <ompl/base/PlannerTerminationCondition.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace test
{
    /// What a search is made of, after its run.
    struct SearchRun
    {
        pushplan::detail::ModelHandlePtr model;
        pushplan::detail::Problem problem;
        std::vector<pushplan::detail::Lane> lanes;
        ompl::base::PlannerPtr planner;
    };

    inline pushplan::detail::ModelHandlePtr load(const std::string &scene)
    {
        return std::make_shared<pushplan::detail::ModelHandle>(pushplan::bridge::Problem::load(scene));
    }

    /// A search of `kind` on `scene` from `seed`, with `lanes` lanes (0: OMPL's planner
    /// itself) run by `threads` threads (0: one per lane), the given restart and fallback
    /// budgets (0: none), until it solves or has taken `budget` propagation steps.
    inline SearchRun runSearch(const std::string &scene, pushplan::PlannerKind kind, std::uint64_t seed,
                               unsigned lanes, unsigned threads, std::uint64_t restart_steps,
                               std::uint64_t fallback_steps, std::uint64_t budget)
    {
        namespace pd = pushplan::detail;
        SearchRun run;
        run.model = load(scene);
        const unsigned k = run.model->info().planner.k;
        run.problem = pd::makeProblem(run.model, seed, k);
        for (unsigned i = 0; i < lanes; ++i)
            run.lanes.push_back(pd::makeLane(run.problem, load(scene), seed, i));
        run.planner = pd::makePlanner(kind, run.problem, seed, 0.05, false, restart_steps, fallback_steps, run.lanes,
                                      threads);
        run.problem.setup->setPlanner(run.planner);
        run.problem.setup->setup();
        const pd::ModelHandlePtr &model = run.model;
        run.planner->solve(
            ompl::base::PlannerTerminationCondition([&] { return model->propagationSteps() >= budget; }));
        return run;
    }

    inline bool samePath(const pushplan::detail::FlatPath &a,
                         const pushplan::detail::FlatPath &b)
    {
        return a.controls == b.controls && a.steps == b.steps && a.states == b.states;
    }
}  // namespace test
