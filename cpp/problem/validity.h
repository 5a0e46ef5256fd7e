// State validity through the Rust model (Sec. II-A).
#pragma once

#include "pushplan/cpp/problem/model_handle.h"

#include <ompl/base/StateValidityChecker.h>

namespace pushplan::detail
{
    /// Bounds (joint limits, table) and every validity rule of the model.
    class PushValidityChecker : public ompl::base::StateValidityChecker
    {
    public:
        PushValidityChecker(const ompl::base::SpaceInformationPtr &si, ModelHandlePtr model);
        bool isValid(const ompl::base::State *state) const override;

    private:
        ModelHandlePtr model_;
    };
}  // namespace pushplan::detail
