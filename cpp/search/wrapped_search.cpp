#include "pushplan/cpp/search/wrapped_search.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>

#include <limits>
#include <utility>

namespace ob = ompl::base;

namespace pushplan::detail
{
    WrappedSearch::WrappedSearch(ob::PlannerPtr search)
      : ob::Planner(search->getSpaceInformation(), search->getName()), search_(std::move(search))
    {
        specs_ = search_->getSpecs();
        params_.include(search_->params());
        plannerProgressProperties_ = search_->getPlannerProgressProperties();
    }

    void WrappedSearch::clear()
    {
        ob::Planner::clear();
        search_->clear();
    }

    void WrappedSearch::setup()
    {
        ob::Planner::setup();
        search_->setup();
    }

    void WrappedSearch::setProblemDefinition(const ob::ProblemDefinitionPtr &pdef)
    {
        ob::Planner::setProblemDefinition(pdef);
        search_->setProblemDefinition(pdef);
    }

    void WrappedSearch::getPlannerData(ob::PlannerData &data) const
    {
        search_->getPlannerData(data);
    }

    void WrappedSearch::checkValidity()
    {
        ob::Planner::checkValidity();
        search_->checkValidity();
    }

    TimeLimitedSearch::TimeLimitedSearch(ob::PlannerPtr search, std::vector<ModelHandlePtr> models, double seconds)
      : WrappedSearch(std::move(search)), models_(std::move(models)), seconds_(seconds)
    {
    }

    ob::PlannerStatus TimeLimitedSearch::solve(const ob::PlannerTerminationCondition &ptc)
    {
        struct Lift
        {
            const std::vector<ModelHandlePtr> &models;
            ~Lift()
            {
                for (const ModelHandlePtr &m : models)
                    m->propagator().set_time_limit(std::numeric_limits<double>::infinity());
            }
        };
        for (const ModelHandlePtr &m : models_)
            m->propagator().set_time_limit(seconds_);
        const Lift lift{models_};
        return search_->solve(ptc);
    }

    const ob::Planner &innerPlanner(const ob::PlannerPtr &planner)
    {
        const ob::Planner *p = planner.get();
        while (const auto *wrapped = dynamic_cast<const WrappedSearch *>(p))
            p = wrapped->search().get();
        return *p;
    }
}  // namespace pushplan::detail
