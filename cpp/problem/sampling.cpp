#include "pushplan/cpp/problem/sampling.h"

#include <cmath>

namespace pushplan::detail
{
    void sampleJoints(const bridge::SceneInfo &info, ompl::RNG &rng, double *out)
    {
        for (std::size_t i = 0; i < info.dof; ++i)
            out[i] = rng.uniformReal(info.joint_lower[i], info.joint_upper[i]);
    }

    std::array<double, 2> sampleOnTable(const bridge::SceneInfo &info, ompl::RNG &rng)
    {
        const double x = rng.uniformReal(info.table[0], info.table[1]);
        return {x, rng.uniformReal(info.table[2], info.table[3])};
    }

    std::array<double, 2> sampleInGoalDisc(const bridge::SceneInfo &info, ompl::RNG &rng)
    {
        const double r = info.goal_radius * std::sqrt(rng.uniform01());
        const double a = rng.uniformReal(-M_PI, M_PI);
        return {info.goal_center[0] + r * std::cos(a), info.goal_center[1] + r * std::sin(a)};
    }

    double sampleYaw(ompl::RNG &rng)
    {
        return rng.uniformReal(-M_PI, M_PI);
    }
}  // namespace pushplan::detail
