// Planners that run another planner, their search, and add one thing to it: restarts
// (restarts.h), or the model's time limit (TimeLimitedSearch). Each carries its search's
// name, specs, parameters and progress properties, so OMPL's tooling (benchmark logs,
// Planner Arena) sees the search.
#pragma once

#include "model_handle.h"

#include <ompl/base/Planner.h>

namespace pushplan::detail
{
    /// A planner that forwards all but solve() to its search.
    class WrappedSearch : public ompl::base::Planner
    {
    public:
        explicit WrappedSearch(ompl::base::PlannerPtr search);

        void clear() override;
        void setup() override;
        void setProblemDefinition(const ompl::base::ProblemDefinitionPtr &pdef) override;
        void getPlannerData(ompl::base::PlannerData &data) const override;
        void checkValidity() override;

        const ompl::base::PlannerPtr &search() const { return search_; }

    protected:
        ompl::base::PlannerPtr search_;
    };

    /// The search under a time limit its model enforces: from the start of solve(), no
    /// propagation past `seconds` (an extension of k long controls ends on time, where
    /// OMPL checks its termination condition only between extensions); lifted when
    /// solve() returns: after the search, OMPL's Benchmark re-propagates the path it
    /// checks. PDST runs without it (`PlannerKind::cut_at_time_limit`): it propagates its
    /// motions again within its search and to return its path.
    class TimeLimitedSearch : public WrappedSearch
    {
    public:
        TimeLimitedSearch(ompl::base::PlannerPtr search, ModelHandlePtr model, double seconds);

        ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;

    private:
        ModelHandlePtr model_;
        double seconds_;
    };

    /// The planner a search runs: `planner` itself, or the innermost search of wrappers.
    const ompl::base::Planner &innerPlanner(const ompl::base::PlannerPtr &planner);
}  // namespace pushplan::detail
