#include "pushplan/cpp/search/fallback.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/control/SimpleSetup.h>

#include <atomic>
#include <cmath>
#include <utility>

namespace ob = ompl::base;

namespace pushplan::detail
{
    Fallback::Fallback(ob::PlannerPtr search, std::vector<Search> fallbacks, ModelHandlePtr model,
                       std::uint64_t patience_steps)
      : WrappedSearch(search)
      , first_(std::move(search))
      , fallbacks_(std::move(fallbacks))
      , credited_steps_(fallbacks_.size(), 0)
      , credited_seconds_(fallbacks_.size(), 0.0)
      , model_(std::move(model))
      , patience_steps_(patience_steps)
    {
        if (fallbacks_.size() == 0)
            throw Error("a fallback needs at least one search to hand over to");
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
            // The hand never got to the goal object: the first tree goes, the fallbacks
            // search from the start, their models' counts credited from here on.
            search_->clear();
            search_ = fallbacks_[0].planner;
            for (std::size_t i = 0; i < fallbacks_.size(); ++i)
            {
                const ob::ProblemDefinitionPtr &pdef = fallbacks_[i].problem.setup->getProblemDefinition();
                pdef->clearStartStates();
                pdef->addStartState(pdef_->getStartState(0));
                credited_steps_[i] = fallbacks_[i].problem.model->propagationSteps();
                credited_seconds_[i] = fallbacks_[i].problem.model->propagationSeconds();
            }
            if (ptc())
                return status;
        }
        return solveWithFallbacks(ptc);
    }

    ob::PlannerStatus Fallback::solveWithFallbacks(const ob::PlannerTerminationCondition &ptc)
    {
        ob::PlannerStatus status = ob::PlannerStatus::TIMEOUT;
        if (fallbacks_.size() == 1)
            status = fallbacks_[0].planner->solve(ptc);
        else
        {
            // The caller's termination condition is asked on this thread only, once a round
            // (its own rounds may pause there: Portfolio's lone search); the fallbacks'
            // threads read the answer.
            std::atomic<bool> stop{false};
            fallbacks_.solve([&] { return stop.load(); }, [] { return true; },
                             [&] {
                                 creditFallbacks();
                                 stop = ptc();
                             });
            creditFallbacks();
        }
        const std::optional<std::size_t> best = fallbacks_.best();
        if (!best)
            return status;
        const ob::ProblemDefinitionPtr &found = fallbacks_[*best].problem.setup->getProblemDefinition();
        pdef_->addSolutionPath(found->getSolutions().front());
        return found->hasExactSolution() ? ob::PlannerStatus::EXACT_SOLUTION : ob::PlannerStatus::APPROXIMATE_SOLUTION;
    }

    void Fallback::creditFallbacks()
    {
        for (std::size_t i = 1; i < fallbacks_.size(); ++i)
        {
            const ModelHandle &model = *fallbacks_[i].problem.model;
            model_->credit(model.propagationSteps() - credited_steps_[i],
                           model.propagationSeconds() - credited_seconds_[i]);
            credited_steps_[i] = model.propagationSteps();
            credited_seconds_[i] = model.propagationSeconds();
            // Infinite while the model has met no goal distance.
            for (const double distance : {model.closestGoalDistance(), model.farthestGoalDistance()})
                if (std::isfinite(distance))
                    model_->creditGoalDistance(distance);
        }
    }

    void Fallback::clear()
    {
        ob::Planner::clear();
        for (std::size_t i = 0; i < fallbacks_.size(); ++i)
            fallbacks_.restart(i);
        // Once handed over, the fallbacks start over (robust planning sets a solution
        // aside and searches anew): that the first search could not move the goal object
        // is the scene's doing, not its tree's. Back in the first search it would not hand
        // over again, as the model's goal distances now hold the fallbacks' moves.
        if (fellBack())
            return;
        first_->clear();
        began_at_ = model_->propagationSteps();
        kept_ = false;
    }

    void Fallback::setup()
    {
        ob::Planner::setup();
        first_->setup();
        for (std::size_t i = 0; i < fallbacks_.size(); ++i)
            fallbacks_[i].problem.setup->setup();
    }

    void Fallback::setProblemDefinition(const ob::ProblemDefinitionPtr &pdef)
    {
        ob::Planner::setProblemDefinition(pdef);
        first_->setProblemDefinition(pdef);
        // The fallbacks keep problem definitions of their own, given this one's start as
        // they take over.
        start_distance_.reset();  // another start, maybe
    }

    void Fallback::getPlannerData(ob::PlannerData &data) const
    {
        if (!fellBack())
        {
            WrappedSearch::getPlannerData(data);
            return;
        }
        for (std::size_t i = 0; i < fallbacks_.size(); ++i)
            fallbacks_[i].planner->getPlannerData(data);
    }

    bool fellBack(const ob::PlannerPtr &planner)
    {
        const Fallback *fallback = wrapperOf<Fallback>(planner);
        return fallback != nullptr && fallback->fellBack();
    }
}  // namespace pushplan::detail
