// Goals: the goal object's centre in a disc, a robot configuration, or the tool in a grasp
// region of an object. All can be sampled (grasps through inverse kinematics), so RRT's
// goal bias works.
#pragma once

#include "pushplan/cpp/problem/model_handle.h"

#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/util/RandomNumbers.h>

namespace pushplan::detail
{
    /// X_G = states whose goal object's centre is in the disc (or whose robot is within
    /// tolerance of the goal configuration, or whose tool is in a grasp region). distanceGoal is the model's signed distance
    /// to the region (m or rad), negative inside. Samples are targets in the region: the goal
    /// object in its disc, the rest uniform, valid or not (isValid tells).
    class PushGoal : public ompl::base::GoalSampleableRegion
    {
    public:
        PushGoal(const ompl::base::SpaceInformationPtr &si, ModelHandlePtr model, std::uint_fast32_t seed);
        double distanceGoal(const ompl::base::State *state) const override;
        void sampleGoal(ompl::base::State *state) const override;
        unsigned int maxSampleCount() const override;

    private:
        /// A grasp goal's sample: the objects at their start, the arm at an IK solution of
        /// one of the object's grasp regions; false if the try found none.
        bool sampleGrasp(ompl::base::State *state) const;

        ModelHandlePtr model_;
        mutable ompl::RNG rng_;
        mutable std::vector<double> buffer_;
    };
}  // namespace pushplan::detail
