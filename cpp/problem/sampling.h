// The random draws every sampler of the problem shares: the state sampler, the goal
// region's sampler and DARRT's (one definition of "uniform" for each part of a state).
#pragma once

#include "pushplan/src/bridge.rs.h"

#include <ompl/util/RandomNumbers.h>

#include <array>

namespace pushplan::detail
{
    /// Joint values uniform within their limits, into out[0 .. dof).
    void sampleJoints(const bridge::SceneInfo &info, ompl::RNG &rng, double *out);
    /// An object's position (x, y in m, world frame) uniform over the table.
    std::array<double, 2> sampleOnTable(const bridge::SceneInfo &info, ompl::RNG &rng);
    /// A position uniform over the goal disc (radius ~ R sqrt(u), angle uniform).
    std::array<double, 2> sampleInGoalDisc(const bridge::SceneInfo &info, ompl::RNG &rng);
    /// A yaw (rad) uniform in [-pi, pi).
    double sampleYaw(ompl::RNG &rng);
}  // namespace pushplan::detail
