// The action space (Sec. III-C): end-effector planar velocities with a null-space sample.
#pragma once

#include "model_handle.h"

#include <ompl/control/ControlSampler.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

namespace pushplan::detail
{
    /// Controls (vx, vy, omega_z, z_1 .. z_n): bounds from the scene's planner section.
    std::shared_ptr<ompl::control::RealVectorControlSpace> makeControlSpace(const ompl::base::StateSpacePtr &space,
                                                                           const bridge::SceneInfo &info);

    /// Samples actions uniformly within the bounds, each with its own null-space sample.
    class EeControlSampler : public ompl::control::ControlSampler
    {
    public:
        EeControlSampler(const ompl::control::ControlSpace *space, std::uint_fast32_t seed);
        void sample(ompl::control::Control *control) override;
        void sample(ompl::control::Control *control, const ompl::base::State *state) override;
        void sampleNext(ompl::control::Control *control, const ompl::control::Control *previous) override;
        void sampleNext(ompl::control::Control *control, const ompl::control::Control *previous,
                        const ompl::base::State *state) override;
    };
}  // namespace pushplan::detail
