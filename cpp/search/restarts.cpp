#include "pushplan/cpp/search/restarts.h"

#include <ompl/base/ProblemDefinition.h>

#include <limits>
#include <stdexcept>
#include <utility>

namespace ob = ompl::base;

namespace pushplan::detail
{
    std::uint64_t luby(std::uint64_t i)
    {
        // i = 2^k - 1 ends a block: its term is 2^(k-1). Otherwise i repeats the sequence
        // from the start of its block.
        for (;;)
        {
            unsigned k = 1;
            while ((std::uint64_t{1} << k) - 1 < i)
                ++k;
            if ((std::uint64_t{1} << k) - 1 == i)
                return std::uint64_t{1} << (k - 1);
            i -= (std::uint64_t{1} << (k - 1)) - 1;
        }
    }

    Restarting::Restarting(ob::PlannerPtr search, ModelHandlePtr model, std::uint64_t base_steps,
                           BeforeAttempt before_attempt)
      : WrappedSearch(std::move(search))
      , model_(std::move(model))
      , base_steps_(base_steps)
      , before_attempt_(std::move(before_attempt))
    {
        if (base_steps_ == 0)
            throw std::invalid_argument("Restarting: the base budget must be at least one step");
    }

    ob::PlannerStatus Restarting::solve(const ob::PlannerTerminationCondition &ptc)
    {
        checkValidity();
        const ModelHandle &model = *model_;
        for (;;)
        {
            if (attempt_end_ && model.propagationSteps() >= *attempt_end_ && !pdef_->hasExactSolution())
            {
                // The attempt's budget is spent without a solution: a new tree.
                search_->clear();
                ++attempt_;
                ++restarts_;
                attempt_end_.reset();
            }
            if (!attempt_end_)
            {
                // Saturating: a budget past 2^64 steps is never reached.
                constexpr std::uint64_t never = std::numeric_limits<std::uint64_t>::max();
                const std::uint64_t factor = luby(attempt_);
                const std::uint64_t budget = base_steps_ > never / factor ? never : base_steps_ * factor;
                const std::uint64_t now = model.propagationSteps();
                attempt_end_ = budget > never - now ? never : now + budget;
                if (before_attempt_)
                    before_attempt_(attempt_);
            }
            const std::uint64_t end = *attempt_end_;
            const ob::PlannerStatus status =
                search_->solve(ob::PlannerTerminationCondition([&] { return ptc() || model.propagationSteps() >= end; }));
            // Solved, or stopped by the caller: the attempt goes on at the next call.
            if (pdef_->hasExactSolution() || model.propagationSteps() < end || ptc())
                return status;
        }
    }

    void Restarting::clear()
    {
        WrappedSearch::clear();
        attempt_ = 1;
        attempt_end_.reset();
    }

    std::uint64_t restartsOf(const ob::PlannerPtr &planner)
    {
        const Restarting *restarting = wrapperOf<Restarting>(planner);
        return restarting ? restarting->restarts() : 0;
    }
}  // namespace pushplan::detail
