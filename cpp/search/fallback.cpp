#include "pushplan/cpp/search/fallback.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/SimpleSetup.h>

#include <atomic>
#include <cmath>
#include <utility>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace pushplan::detail
{
    Fallback::Fallback(ob::PlannerPtr search, std::vector<Search> fallbacks, ModelHandlePtr model,
                       std::uint64_t patience_steps)
      : WrappedSearch(search)
      , first_(std::move(search))
      , fallbacks_(std::move(fallbacks), /*iterations_run_whole=*/false)
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
            handback_distance_ = *start_distance_;
            for (std::size_t i = 0; i < fallbacks_.size(); ++i)
            {
                const ob::ProblemDefinitionPtr &pdef = fallbacks_[i].problem.setup->getProblemDefinition();
                pdef->clearStartStates();
                pdef->addStartState(pdef_->getStartState(0));
                creditedUpToNow(i);
            }
            if (ptc())
                return status;
        }
        return solveWithFallbacks(ptc);
    }

    ob::PlannerStatus Fallback::solveWithFallbacks(const ob::PlannerTerminationCondition &ptc)
    {
        ob::PlannerStatus status = ob::PlannerStatus::TIMEOUT;
        // The fallbacks search until one solves, the time is up, or one's tree holds a
        // state to hand back (then the first search from there; if it brings the goal
        // object no nearer, the fallbacks go on).
        const auto stop_due = [&] { return ptc() || nearerThanHandedBack().has_value(); };
        for (;;)
        {
            if (fallbacks_.size() == 1)
                status = fallbacks_[0].planner->solve(ob::PlannerTerminationCondition(stop_due));
            else
            {
                // The caller's termination condition is asked on this thread only, once a
                // round (its own rounds may pause there: Portfolio's lone search); the
                // fallbacks' threads read the answer.
                std::atomic<bool> stop{false};
                fallbacks_.solve([&](double) { return stop.load(); }, [] { return true; },
                                 [&] {
                                     creditFallbacks();
                                     stop = stop_due();
                                 });
                creditFallbacks();
            }
            const std::optional<std::size_t> best = fallbacks_.best();
            if (best && fallbacks_[*best].problem.setup->getProblemDefinition()->hasExactSolution())
                break;
            const std::optional<std::size_t> nearer = nearerThanHandedBack();
            if (!nearer || ptc())
                break;
            if (searchFromFallback(*nearer, ptc))
                return ob::PlannerStatus::EXACT_SOLUTION;
            if (ptc())
                break;
        }
        const std::optional<std::size_t> best = fallbacks_.best();
        if (!best)
            return status;
        const ob::ProblemDefinitionPtr &found = fallbacks_[*best].problem.setup->getProblemDefinition();
        pdef_->addSolutionPath(found->getSolutions().front());
        return pdef_->hasExactSolution() ? ob::PlannerStatus::EXACT_SOLUTION : ob::PlannerStatus::APPROXIMATE_SOLUTION;
    }

    std::optional<std::size_t> Fallback::nearerThanHandedBack() const
    {
        std::optional<std::size_t> nearest;
        double nearest_distance = handback_distance_;
        for (std::size_t i = 0; i < fallbacks_.size(); ++i)
        {
            const double distance = fallbacks_[i].problem.model->goal().closest_distance();
            if (distance < nearest_distance)
                nearest = i, nearest_distance = distance;
        }
        return nearest;
    }

    bool Fallback::searchFromFallback(std::size_t i, const ob::PlannerTerminationCondition &ptc)
    {
        // The state is handed back once, whatever follows: only a nearer one is handed back
        // next.
        handback_distance_ = fallbacks_[i].problem.model->goal().closest_distance();
        // The fallback stopped with that state in its tree: OMPL's RRT gives the path to it
        // as its approximate solution, the best of its problem definition's (every state
        // it met before is farther from the goal).
        const ob::ProblemDefinitionPtr &reached = fallbacks_[i].problem.setup->getProblemDefinition();
        if (!reached->hasSolution())
            return false;
        // (getSolutions() returns a copy.)
        const ob::PlannerSolution to_state = reached->getSolutions().front();
        const auto prefix = std::dynamic_pointer_cast<oc::PathControl>(to_state.path_);
        if (!prefix || prefix->getStateCount() == 0)
            return false;
        ++handed_back_;

        auto from = std::make_shared<ob::ProblemDefinition>(si_);
        from->addStartState(prefix->getStates().back());
        from->setGoal(pdef_->getGoal());
        first_->clear();
        first_->setProblemDefinition(from);
        const std::uint64_t end = model_->propagationSteps() + patience_steps_;
        first_->solve(ob::PlannerTerminationCondition([&] { return ptc() || model_->propagationSteps() >= end; }));
        // As before the handover: a search that has brought the goal object nearer the goal
        // keeps the problem; one that has not goes back to the fallbacks.
        if (!from->hasExactSolution() && from->hasSolution() && from->getSolutionDifference() < handback_distance_)
            first_->solve(ptc);
        first_->setProblemDefinition(pdef_);
        // What the fallbacks meet from here on is theirs alone: the first search's states,
        // met on the same models, must not hand back again, and its lanes' steps, credited
        // by the search itself, are not the fallbacks' to credit.
        for (std::size_t f = 0; f < fallbacks_.size(); ++f)
        {
            fallbacks_[f].problem.model->restartGoalWatch();
            creditedUpToNow(f);
        }
        if (!from->hasSolution())
            return false;
        // The fallback's path to the state, then the first search's path from it.
        const ob::PlannerSolution onward = from->getSolutions().front();
        auto joined = std::make_shared<oc::PathControl>(*prefix);
        const auto &tail = *onward.path_->as<oc::PathControl>();
        for (std::size_t k = 0; k < tail.getControlCount(); ++k)
            joined->append(tail.getState(k + 1), tail.getControl(k), tail.getControlDuration(k));
        pdef_->addSolutionPath(joined, onward.approximate_, onward.difference_, getName());
        return !onward.approximate_;
    }

    void Fallback::creditFallbacks()
    {
        for (std::size_t i = 1; i < fallbacks_.size(); ++i)
        {
            const ModelHandle &model = *fallbacks_[i].problem.model;
            model_->credit(model.propagationSteps() - credited_steps_[i],
                           model.propagationSeconds() - credited_seconds_[i]);
            creditedUpToNow(i);
            // Infinite while the model has met no goal distance.
            for (const double distance : {model.closestGoalDistance(), model.farthestGoalDistance()})
                if (std::isfinite(distance))
                    model_->creditGoalDistance(distance);
        }
    }

    void Fallback::creditedUpToNow(std::size_t i)
    {
        const ModelHandle &model = *fallbacks_[i].problem.model;
        credited_steps_[i] = model.propagationSteps();
        credited_seconds_[i] = model.propagationSeconds();
    }

    void Fallback::clear()
    {
        ob::Planner::clear();
        first_->clear();
        for (std::size_t i = 0; i < fallbacks_.size(); ++i)
            fallbacks_.restart(i);
        // Once handed over, the fallbacks start over (robust planning sets a solution
        // aside and searches anew): that the first search could not move the goal object
        // is the scene's doing, not its tree's. Back in the first search it would not hand
        // over again, as the model's goal distances now hold the fallbacks' moves. What
        // the new fallback trees meet may hand back again.
        if (fellBack())
        {
            handback_distance_ = *start_distance_;
            for (std::size_t i = 0; i < fallbacks_.size(); ++i)
                fallbacks_[i].problem.model->restartGoalWatch();
            return;
        }
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
        // The first search's tree from the last state handed back.
        if (handed_back_ > 0)
            first_->getPlannerData(data);
    }

    bool fellBack(const ob::PlannerPtr &planner)
    {
        const Fallback *fallback = wrapperOf<Fallback>(planner);
        return fallback != nullptr && fallback->fellBack();
    }

    std::uint64_t handedBack(const ob::PlannerPtr &planner)
    {
        const Fallback *fallback = wrapperOf<Fallback>(planner);
        return fallback != nullptr ? fallback->handedBack() : 0;
    }
}  // namespace pushplan::detail
