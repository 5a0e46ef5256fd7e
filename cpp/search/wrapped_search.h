// Planners that run another planner, their search, and add one thing to it: restarts
// (restarts.h), or the model's time limit (TimeLimitedSearch). Each carries its search's
// name, specs, parameters and progress properties, so OMPL's tooling (benchmark logs,
// Planner Arena) sees the search.
#pragma once

#include "pushplan/cpp/problem/model_handle.h"

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

        /// The search running now.
        const ompl::base::PlannerPtr &search() const { return search_; }
        /// The search this planner was made around: the one running, but for a planner
        /// that hands over to another (Fallback), whose first search this is.
        virtual const ompl::base::PlannerPtr &wrapped() const { return search_; }

    protected:
        ompl::base::PlannerPtr search_;
    };

    /// The first planner of type `Wrapper` in `planner`'s chain of wrappers (itself
    /// included, each followed to the search it was made around), or null.
    template <class Wrapper>
    const Wrapper *wrapperOf(const ompl::base::PlannerPtr &planner)
    {
        const ompl::base::Planner *p = planner.get();
        while (const auto *wrapped = dynamic_cast<const WrappedSearch *>(p))
        {
            if (const auto *found = dynamic_cast<const Wrapper *>(wrapped))
                return found;
            p = wrapped->wrapped().get();
        }
        return nullptr;
    }

    /// The search under a time limit its models enforce (its own, and its lanes' where its
    /// propagations run on several): from the start of solve(), no
    /// propagation past `seconds` (an extension of k long controls ends on time, where
    /// OMPL checks its termination condition only between extensions); lifted when
    /// solve() returns: after the search, OMPL's Benchmark re-propagates the path it
    /// checks. PDST runs without it (`PlannerKind::cut_at_time_limit`): it propagates its
    /// motions again within its search and to return its path.
    class TimeLimitedSearch : public WrappedSearch
    {
    public:
        TimeLimitedSearch(ompl::base::PlannerPtr search, std::vector<ModelHandlePtr> models, double seconds);

        ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;

    private:
        std::vector<ModelHandlePtr> models_;
        double seconds_;
    };

    /// The planner a search runs: `planner` itself, or the innermost search of wrappers.
    const ompl::base::Planner &innerPlanner(const ompl::base::PlannerPtr &planner);
}  // namespace pushplan::detail
