#include "pushplan/cpp/problem/control.h"

#include "pushplan/cpp/problem/sampling.h"

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

    PushControlSampler::PushControlSampler(const oc::ControlSpace *space, std::uint_fast32_t seed,
                                           const ModelHandle &model, PushMix mix)
      : EeControlSampler(space, seed),
        view_(model.view()),
        projection_(bridge::Projection::make(model.problem())),
        mix_(mix)
    {
    }

    void PushControlSampler::sample(oc::Control *control, const ob::State *state)
    {
        EeControlSampler::sample(control);
        const bridge::SceneInfo &info = view_->info();
        if (info.goal_object < 0 || rng_.uniform01() >= mix_.guided)
            return;
        // A push: a blocker out of the goal object's way, or the goal object toward the goal
        // disc, or (a detour) toward anywhere on the table.
        bridge::PushTarget push{static_cast<std::size_t>(info.goal_object), {}};
        view_->read(state, buffer_);
        const rust::Vec<bridge::PushTarget> blockers = projection_->push_blockers(slice(buffer_));
        if (!blockers.empty() && rng_.uniform01() < mix_.clear)
            push = blockers[rng_.uniformInt(0, static_cast<int>(blockers.size()) - 1)];
        else
        {
            const std::array<double, 2> p =
                rng_.uniform01() < mix_.to_goal ? sampleInGoalDisc(info, rng_) : sampleOnTable(info, rng_);
            push.target = {p[0], p[1]};
        }
        const rust::Vec<double> heading =
            projection_->push_heading(slice(buffer_), push.object, {push.target.data(), push.target.size()});
        if (heading.empty())
            return;
        // The end-effector velocity (m/s) along the heading.
        const double max_speed = info.planner.max_ee_speed;
        const double speed = rng_.uniformReal(0.5 * max_speed, max_speed);
        double *values = control->as<oc::RealVectorControlSpace::ControlType>()->values;
        values[0] = speed * heading[0];
        values[1] = speed * heading[1];
    }

    void PushControlSampler::sampleNext(oc::Control *control, const oc::Control *, const ob::State *state)
    {
        sample(control, state);
    }
}  // namespace pushplan::detail
