#include "control.h"

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace pushplan::detail
{
    std::shared_ptr<oc::RealVectorControlSpace> makeControlSpace(const ob::StateSpacePtr &space,
                                                                 const bridge::SceneInfo &info)
    {
        auto controls = std::make_shared<oc::RealVectorControlSpace>(space, 3 + info.dof);
        ob::RealVectorBounds bounds(3 + info.dof);
        bounds.setLow(0, -info.planner.max_ee_speed);
        bounds.setHigh(0, info.planner.max_ee_speed);
        bounds.setLow(1, -info.planner.max_ee_speed);
        bounds.setHigh(1, info.planner.max_ee_speed);
        bounds.setLow(2, -info.planner.max_ee_turn_rate);
        bounds.setHigh(2, info.planner.max_ee_turn_rate);
        for (std::size_t i = 0; i < info.dof; ++i)
        {
            bounds.setLow(3 + i, -info.planner.max_nullspace_speed);
            bounds.setHigh(3 + i, info.planner.max_nullspace_speed);
        }
        controls->setBounds(bounds);
        return controls;
    }

    EeControlSampler::EeControlSampler(const oc::ControlSpace *space, std::uint_fast32_t seed)
      : oc::ControlSampler(space)
    {
        rng_.setLocalSeed(seed);
    }

    void EeControlSampler::sample(oc::Control *control)
    {
        const auto &bounds = space_->as<oc::RealVectorControlSpace>()->getBounds();
        double *values = control->as<oc::RealVectorControlSpace::ControlType>()->values;
        for (std::size_t i = 0; i < bounds.low.size(); ++i)
            values[i] = rng_.uniformReal(bounds.low[i], bounds.high[i]);
    }

    // Every action is sampled afresh (Alg. 1, line 6): neither the state nor the previous
    // action biases it.
    void EeControlSampler::sample(oc::Control *control, const ob::State *)
    {
        sample(control);
    }

    void EeControlSampler::sampleNext(oc::Control *control, const oc::Control *)
    {
        sample(control);
    }

    void EeControlSampler::sampleNext(oc::Control *control, const oc::Control *, const ob::State *)
    {
        sample(control);
    }
}  // namespace pushplan::detail
