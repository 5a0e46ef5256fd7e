#include "restarts.h"

#include <ompl/base/PlannerData.h>
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

    Restarting::Restarting(ob::PlannerPtr search, ModelHandlePtr model, std::uint64_t base_steps)
      : ob::Planner(search->getSpaceInformation(), search->getName())
      , search_(std::move(search))
      , model_(std::move(model))
      , base_steps_(base_steps)
    {
        if (base_steps_ == 0)
            throw std::invalid_argument("Restarting: the base budget must be at least one step");
        specs_ = search_->getSpecs();
        params_.include(search_->params());
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
        ob::Planner::clear();
        search_->clear();
        attempt_ = 1;
        attempt_end_.reset();
    }

    void Restarting::setup()
    {
        ob::Planner::setup();
        search_->setup();
    }

    void Restarting::setProblemDefinition(const ob::ProblemDefinitionPtr &pdef)
    {
        ob::Planner::setProblemDefinition(pdef);
        search_->setProblemDefinition(pdef);
    }

    void Restarting::getPlannerData(ob::PlannerData &data) const
    {
        search_->getPlannerData(data);
    }

    void Restarting::checkValidity()
    {
        ob::Planner::checkValidity();
        search_->checkValidity();
    }

    std::uint64_t restartsOf(const ob::PlannerPtr &planner)
    {
        const auto *restarting = dynamic_cast<const Restarting *>(planner.get());
        return restarting ? restarting->restarts() : 0;
    }

    const ob::Planner &innerPlanner(const ob::PlannerPtr &planner)
    {
        if (const auto *restarting = dynamic_cast<const Restarting *>(planner.get()))
            return *restarting->search();
        return *planner;
    }
}  // namespace pushplan::detail
