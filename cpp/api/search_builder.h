// The one way the searches of a scene are built: Planner::solve's (one per thread, or one
// on lanes), a benchmark run's, and makeSetup's problem.
#pragma once

#include "pushplan/cpp/problem/bridge_types.h"
#include "pushplan/cpp/problem/model_handle.h"
#include "pushplan/cpp/problem/problem.h"

#include <ompl/base/Planner.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace pushplan::detail
{
    /// A search ready to set up: its problem, its planner, and every model it propagates
    /// with (the problem's first, then its lanes').
    struct BuiltSearch
    {
        Problem problem;
        ompl::base::PlannerPtr planner;
        std::vector<ModelHandlePtr> models;
    };

    /// Builds the searches of one scene: loads a model per search and per lane, pins the
    /// clutter in Static RRT's problem, carries the perturbed worlds of robust planning,
    /// and makes the problem, the lanes and the planner. The time limit stays with the
    /// caller: Planner::solve's runs from before its searches start, a benchmark run's
    /// from each solve() (TimeLimitedSearch).
    class SearchBuilder
    {
    public:
        using Load = std::function<rust::Box<bridge::Problem>()>;

        /// Loads the scene now (to read it; the model serves the first search).
        explicit SearchBuilder(Load load);

        const bridge::SceneInfo &info() const { return first_->info(); }

        /// A model of the scene, in Static RRT's problem (the clutter pinned where it
        /// starts) or the pushing one, carrying `particles` perturbed worlds drawn from
        /// `particle_seed` (none: 0).
        ModelHandlePtr model(bool static_clutter, unsigned particles = 0, std::uint64_t particle_seed = 0);

        /// One search as `run` says, seeded with `seed` (its perturbed worlds too), on
        /// `lanes` lanes of models of its own (0: none).
        BuiltSearch search(const RunSettings &run, std::uint64_t seed, unsigned lanes);

    private:
        Load load_;
        /// The model loaded first, until a search takes it.
        ModelHandlePtr first_;
        bool first_taken_ = false;
    };
}  // namespace pushplan::detail
