#include "pushplan/cpp/problem/propagator.h"

#include <cmath>

namespace pushplan::detail
{
    PushStatePropagator::PushStatePropagator(const ompl::control::SpaceInformationPtr &si, ModelHandlePtr model)
      : ompl::control::StatePropagator(si), model_(std::move(model))
    {
    }

    void PushStatePropagator::propagate(const ompl::base::State *state, const ompl::control::Control *control,
                                        double duration, ompl::base::State *result) const
    {
        const double steps = std::round(duration / model_->info().planner.step);
        model_->propagate(state, control, steps > 0.0 ? static_cast<std::size_t>(steps) : 0, result);
    }
}  // namespace pushplan::detail
