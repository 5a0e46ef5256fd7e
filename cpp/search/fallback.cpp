#include "pushplan/cpp/search/fallback.h"

#include <ompl/base/ProblemDefinition.h>

#include <utility>

namespace ob = ompl::base;

namespace pushplan::detail
{
    Fallback::Fallback(ob::PlannerPtr search, ob::PlannerPtr fallback, ModelHandlePtr model,
                       std::uint64_t patience_steps)
      : WrappedSearch(search)
      , first_(std::move(search))
      , fallback_(std::move(fallback))
      , model_(std::move(model))
      , patience_steps_(patience_steps)
    {
        began_at_ = model_->propagationSteps();
    }

    bool Fallback::handOverDue()
    {
        if (kept_ || model_->propagationSteps() < began_at_ + patience_steps_)
            return false;
        // The model keeps the least and the largest goal distance its search has met: both
        // the start's while no state has moved the goal object.
        kept_ = model_->closestGoalDistance() < *start_distance_ || model_->farthestGoalDistance() > *start_distance_;
        return !kept_;
    }

    ob::PlannerStatus Fallback::solve(const ob::PlannerTerminationCondition &ptc)
    {
        checkValidity();
        if (!start_distance_)
            start_distance_ = model_->goalDistance(pdef_->getStartState(0));
        if (!fellBack())
        {
            const ob::PlannerStatus status =
                search_->solve(ob::PlannerTerminationCondition([&] { return ptc() || handOverDue(); }));
            if (pdef_->hasExactSolution() || !handOverDue())
                return status;
            // The hand never got to the goal object: the first tree goes, the fallback
            // searches from the start.
            search_->clear();
            search_ = fallback_;
            if (ptc())
                return status;
        }
        return search_->solve(ptc);
    }

    void Fallback::clear()
    {
        ob::Planner::clear();
        first_->clear();
        fallback_->clear();
        search_ = first_;
        began_at_ = model_->propagationSteps();
        kept_ = false;
    }

    void Fallback::setup()
    {
        ob::Planner::setup();
        first_->setup();
        fallback_->setup();
    }

    void Fallback::setProblemDefinition(const ob::ProblemDefinitionPtr &pdef)
    {
        ob::Planner::setProblemDefinition(pdef);
        first_->setProblemDefinition(pdef);
        fallback_->setProblemDefinition(pdef);
        start_distance_.reset();  // another start, maybe
    }

    bool fellBack(const ob::PlannerPtr &planner)
    {
        const Fallback *fallback = wrapperOf<Fallback>(planner);
        return fallback != nullptr && fallback->fellBack();
    }
}  // namespace pushplan::detail
