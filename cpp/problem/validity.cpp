#include "pushplan/cpp/problem/validity.h"

#include <ompl/base/SpaceInformation.h>

namespace pushplan::detail
{
    PushValidityChecker::PushValidityChecker(const ompl::base::SpaceInformationPtr &si, const ModelHandle &model)
      : ompl::base::StateValidityChecker(si),
        view_(model.view()),
        validity_(bridge::ValidityChecker::make(model.problem()))
    {
    }

    bool PushValidityChecker::isValid(const ompl::base::State *state) const
    {
        // isValid does not check bounds by itself (ompl.md); the model does: its rules imply
        // them (joint limits, footprints on the table) and it checks every yaw is within
        // [-pi, pi]. OMPL's satisfiesBounds through the compound space was 4 % of a dense
        // search's time (BENCHMARKS.md).
        view_->read(state, buffer_);
        return validity_->is_valid(slice(buffer_), view_->particles(state));
    }
}  // namespace pushplan::detail
