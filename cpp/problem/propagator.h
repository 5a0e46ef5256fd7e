// ConstrainedProp (Alg. 2) as an OMPL state propagator.
#pragma once

#include "pushplan/cpp/problem/model_handle.h"

#include <ompl/control/StatePropagator.h>

namespace pushplan::detail
{
    /// Holds a control for a duration through the Rust model: projection onto the
    /// pushing plane, quasistatic pushing, validity. Deterministic; safe when
    /// state == result. A step that is invalid leaves the invalid state in `result`
    /// (OMPL's propagateWhileValid then asks isValid and stops there).
    class PushStatePropagator : public ompl::control::StatePropagator
    {
    public:
        PushStatePropagator(const ompl::control::SpaceInformationPtr &si, ModelHandlePtr model);
        void propagate(const ompl::base::State *state, const ompl::control::Control *control, double duration,
                       ompl::base::State *result) const override;
        bool canPropagateBackward() const override { return false; }

    private:
        ModelHandlePtr model_;
    };
}  // namespace pushplan::detail
