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
        /// The checker of `model`'s problem (a part of its own).
        PushValidityChecker(const ompl::base::SpaceInformationPtr &si, const ModelHandle &model);
        bool isValid(const ompl::base::State *state) const override;

    private:
        std::shared_ptr<const StateView> view_;
        rust::Box<bridge::ValidityChecker> validity_;
        mutable std::vector<double> buffer_;
    };
}  // namespace pushplan::detail
