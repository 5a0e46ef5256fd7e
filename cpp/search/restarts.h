// Restarts: a search that has found no solution within a budget of propagation steps
// starts over with a new tree. A sampling-based search of this problem has a
// heavy-tailed time to solve: the same scene solved in 0.1-5 s from five seeds may take
// more than a minute from a sixth, whose tree has grown into a corner it does not leave
// (BENCHMARKS.md, "Restarts"). Budgets follow the Luby sequence times a base (Luby,
// Sinclair and Zuckerman 1993: within a log factor of the best fixed cutoff, whatever
// the distribution), counted in propagation steps, so restarts happen at the same
// iteration whatever the timing.
#pragma once

#include "pushplan/cpp/problem/model_handle.h"
#include "pushplan/cpp/search/wrapped_search.h"

#include <cstdint>
#include <functional>
#include <optional>

namespace pushplan::detail
{
    /// Term i (from 1) of the Luby sequence 1, 1, 2, 1, 1, 2, 4, 1, 1, 2, 1, 1, 2, 4, 8, ...
    std::uint64_t luby(std::uint64_t i);

    /// A planner that restarts its search when an attempt ends without an exact solution:
    /// attempt i may take `base_steps * luby(i)` propagation steps. Approximate solutions
    /// of earlier attempts stay in the problem definition, so the closest path over all
    /// attempts is kept.
    class Restarting : public WrappedSearch
    {
    public:
        /// Called with an attempt's index (from 1) before the attempt starts, on an empty
        /// tree: what changes from one attempt to the next besides the tree (Push KPIECE's
        /// grid cells).
        using BeforeAttempt = std::function<void(std::uint64_t attempt)>;

        /// `before_attempt` may be empty (every attempt as the first).
        Restarting(ompl::base::PlannerPtr search, ModelHandlePtr model, std::uint64_t base_steps,
                   BeforeAttempt before_attempt = {});

        ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
        /// Clears the search and starts the budgets over.
        void clear() override;

        /// Attempts started over for lack of a solution since construction (clear() starts
        /// the budgets over, but does not forget them).
        std::uint64_t restarts() const { return restarts_; }

    private:
        ModelHandlePtr model_;
        std::uint64_t base_steps_;
        BeforeAttempt before_attempt_;
        /// The current attempt's index in the Luby sequence.
        std::uint64_t attempt_ = 1;
        /// The model's step count at which the current attempt ends (unset: not started).
        std::optional<std::uint64_t> attempt_end_;
        std::uint64_t restarts_ = 0;
    };

    /// Restarts of a planner: of the Restarting it is or wraps (0 if none).
    std::uint64_t restartsOf(const ompl::base::PlannerPtr &planner);
}  // namespace pushplan::detail
