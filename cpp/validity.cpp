#include "validity.h"

#include <ompl/base/SpaceInformation.h>

namespace pushplan::detail
{
    PushValidityChecker::PushValidityChecker(const ompl::base::SpaceInformationPtr &si, ModelHandlePtr model)
      : ompl::base::StateValidityChecker(si), model_(std::move(model))
    {
    }

    bool PushValidityChecker::isValid(const ompl::base::State *state) const
    {
        // isValid does not check bounds by itself (ompl.md). The model's rules imply them
        // (joint limits, object centres on the table); the explicit check is cheap.
        return si_->satisfiesBounds(state) && model_->isValid(state);
    }
}  // namespace pushplan::detail
