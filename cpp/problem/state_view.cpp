#include "pushplan/cpp/problem/state_view.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

#include <cmath>
#include <cstdint>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace pushplan::detail
{
    StateView::StateView(std::shared_ptr<const bridge::SceneInfo> info, std::size_t particle_values,
                         bool static_clutter)
      : info_(std::move(info)),
        layout_(stateLayout(info_->dof, info_->objects, particle_values)),
        static_clutter_(static_clutter)
    {
    }

    rust::Slice<const double> StateView::particles(const ob::State *state) const
    {
        const auto *at = reinterpret_cast<const char *>(state) + layout_.particles;
        return {reinterpret_cast<const double *>(at), (layout_.size - layout_.particles) / sizeof(double)};
    }

    rust::Slice<double> StateView::particles(ob::State *state) const
    {
        auto *at = reinterpret_cast<char *>(state) + layout_.particles;
        return {reinterpret_cast<double *>(at), (layout_.size - layout_.particles) / sizeof(double)};
    }

    void StateView::read(const ob::State *state, std::vector<double> &out) const
    {
        out.resize(stateSize());
        const auto *compound = state->as<ob::CompoundState>();
        const double *q = compound->as<ob::RealVectorStateSpace::StateType>(0)->values;
        double *to = out.data();
        for (std::size_t i = 0; i < info_->dof; ++i)
            to[i] = q[i];
        to += info_->dof;
        for (std::size_t i = 0; i < info_->objects; ++i, to += 3)
        {
            const auto *pose = compound->as<ob::SE2StateSpace::StateType>(1 + i);
            to[0] = pose->getX();
            to[1] = pose->getY();
            to[2] = pose->getYaw();
        }
    }

    void StateView::write(const std::vector<double> &in, ob::State *state) const
    {
        auto *compound = state->as<ob::CompoundState>();
        double *q = compound->as<ob::RealVectorStateSpace::StateType>(0)->values;
        std::copy(in.begin(), in.begin() + info_->dof, q);
        for (std::size_t i = 0; i < info_->objects; ++i)
        {
            auto *pose = compound->as<ob::SE2StateSpace::StateType>(1 + i);
            const std::size_t at = flat().object(i);
            pose->setXY(in[at], in[at + 1]);
            pose->setYaw(in[at + 2]);
        }
    }

    void StateView::readControl(const oc::Control *control, std::vector<double> &out) const
    {
        const double *values = control->as<oc::RealVectorControlSpace::ControlType>()->values;
        out.assign(values, values + controlSize());
    }

    FlatPath StateView::readPath(const oc::PathControl &path) const
    {
        FlatPath flat;
        std::vector<double> buffer;
        for (std::size_t i = 0; i < path.getControlCount(); ++i)
        {
            readControl(path.getControl(i), buffer);
            flat.controls.insert(flat.controls.end(), buffer.begin(), buffer.end());
            flat.steps.push_back(static_cast<std::size_t>(std::round(path.getControlDuration(i) / info_->planner.step)));
        }
        for (std::size_t i = 0; i < path.getStateCount(); ++i)
        {
            read(path.getState(i), buffer);
            flat.states.insert(flat.states.end(), buffer.begin(), buffer.end());
        }
        return flat;
    }

    void StateView::pinClutter(std::vector<double> &flat) const
    {
        if (!static_clutter_)
            return;
        for (std::size_t i = 0; i < info_->objects; ++i)
            if (static_cast<std::int64_t>(i) != info_->goal_object)
                for (std::size_t k = 0; k < 3; ++k)
                    flat[this->flat().object(i) + k] = info_->start[this->flat().object(i) + k];
    }
}  // namespace pushplan::detail
