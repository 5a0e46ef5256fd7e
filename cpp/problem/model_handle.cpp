#include "pushplan/cpp/problem/model_handle.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace pushplan::detail
{
    ModelHandle::ModelHandle(rust::Box<bridge::Problem> problem)
      : problem_(std::move(problem)),
        info_(problem_->info()),
        propagator_(bridge::Propagator::make(*problem_)),
        validity_(bridge::ValidityChecker::make(*problem_)),
        metric_(bridge::Metric::make(*problem_)),
        goal_(bridge::Goal::make(*problem_)),
        projection_(bridge::Projection::make(*problem_)),
        finisher_(bridge::Finisher::make(*problem_)),
        darrt_(bridge::Darrt::make(*problem_)),
        grasping_(bridge::Grasping::make(*problem_)),
        layout_(stateLayout(info_.dof, info_.objects, 0))
    {
    }

    void ModelHandle::setParticles(std::size_t count, std::uint64_t seed)
    {
        if (layout_fixed_)
            throw std::logic_error("perturbed worlds must be set before the state space is made");
        problem_->set_particles(count, seed);
        layout_ = stateLayout(info_.dof, info_.objects, problem_->start_particles().size());
    }

    const StateLayout &ModelHandle::fixLayout()
    {
        layout_fixed_ = true;
        return layout_;
    }

    rust::Slice<const double> ModelHandle::particles(const ob::State *state) const
    {
        const auto *at = reinterpret_cast<const char *>(state) + layout_.particles;
        return {reinterpret_cast<const double *>(at), (layout_.size - layout_.particles) / sizeof(double)};
    }

    rust::Slice<double> ModelHandle::particles(ob::State *state) const
    {
        auto *at = reinterpret_cast<char *>(state) + layout_.particles;
        return {reinterpret_cast<double *>(at), (layout_.size - layout_.particles) / sizeof(double)};
    }

    void ModelHandle::writeStart(ob::State *state) const
    {
        write(std::vector<double>(info_.start.begin(), info_.start.end()), state);
        const rust::Vec<double> start = problem_->start_particles();
        std::copy(start.begin(), start.end(), particles(state).begin());
    }

    // The state space is the compound [joints (RealVector), object 1 (SE2), ...].
    void ModelHandle::read(const ob::State *state, std::vector<double> &out) const
    {
        out.resize(stateSize());
        const auto *compound = state->as<ob::CompoundState>();
        const double *q = compound->as<ob::RealVectorStateSpace::StateType>(0)->values;
        double *to = out.data();
        for (std::size_t i = 0; i < info_.dof; ++i)
            to[i] = q[i];
        to += info_.dof;
        for (std::size_t i = 0; i < info_.objects; ++i, to += 3)
        {
            const auto *pose = compound->as<ob::SE2StateSpace::StateType>(1 + i);
            to[0] = pose->getX();
            to[1] = pose->getY();
            to[2] = pose->getYaw();
        }
    }

    void ModelHandle::write(const std::vector<double> &in, ob::State *state) const
    {
        auto *compound = state->as<ob::CompoundState>();
        double *q = compound->as<ob::RealVectorStateSpace::StateType>(0)->values;
        std::copy(in.begin(), in.begin() + info_.dof, q);
        for (std::size_t i = 0; i < info_.objects; ++i)
        {
            auto *pose = compound->as<ob::SE2StateSpace::StateType>(1 + i);
            const std::size_t at = flat().object(i);
            pose->setXY(in[at], in[at + 1]);
            pose->setYaw(in[at + 2]);
        }
    }

    void ModelHandle::readControl(const oc::Control *control, std::vector<double> &out) const
    {
        const double *values = control->as<oc::RealVectorControlSpace::ControlType>()->values;
        out.assign(values, values + controlSize());
    }

    bool ModelHandle::isValid(const ob::State *state) const
    {
        read(state, a_);
        return validity_->is_valid(slice(a_), particles(state));
    }

    double ModelHandle::distance(const ob::State *a, const ob::State *b) const
    {
        // Hot: every distance in a nearest-neighbour query reads two states.
        read(a, a_);
        read(b, b_);
        return metric_->distance(slice(a_), slice(b_));
    }

    double ModelHandle::goalDistance(const ob::State *state) const
    {
        read(state, a_);
        return goal_->distance(slice(a_), particles(state));
    }

    void ModelHandle::pinClutter(std::vector<double> &flat) const
    {
        if (!problem_->static_clutter())
            return;
        for (std::size_t i = 0; i < info_.objects; ++i)
            if (static_cast<std::int64_t>(i) != info_.goal_object)
                for (std::size_t k = 0; k < 3; ++k)
                    flat[this->flat().object(i) + k] = info_.start[this->flat().object(i) + k];
    }

    std::array<double, 5> ModelHandle::project(const ob::State *state) const
    {
        read(state, a_);
        const rust::Vec<double> p = projection_->project(slice(a_));
        return {p[0], p[1], p[2], p[3], p[4]};
    }

    std::optional<std::array<double, 2>> ModelHandle::pushHeading(const ob::State *state, std::size_t object,
                                                                  const std::array<double, 2> &target) const
    {
        read(state, a_);
        const rust::Vec<double> h =
            projection_->push_heading(slice(a_), object, rust::Slice<const double>(target.data(), target.size()));
        if (h.empty())
            return std::nullopt;
        return std::array<double, 2>{h[0], h[1]};
    }

    rust::Vec<bridge::PushTarget> ModelHandle::pushBlockers(const ob::State *state) const
    {
        read(state, a_);
        return projection_->push_blockers(slice(a_));
    }

    bool ModelHandle::propagate(const ob::State *state, const oc::Control *control, std::size_t steps,
                                ob::State *result) const
    {
        read(state, a_);  // copies first: OMPL may pass state == result
        const rust::Slice<const double> from = particles(state);
        particles_.assign(from.begin(), from.end());
        readControl(control, control_);
        b_.resize(a_.size());
        const bool valid = propagator_->propagate(slice(a_), slice(particles_), slice(control_), steps,
                                             rust::Slice<double>(b_.data(), b_.size()), particles(result));
        write(b_, result);
        return valid;
    }

    ModelHandle::FlatPath ModelHandle::readPath(const oc::PathControl &path) const
    {
        FlatPath flat;
        for (std::size_t i = 0; i < path.getControlCount(); ++i)
        {
            readControl(path.getControl(i), control_);
            flat.controls.insert(flat.controls.end(), control_.begin(), control_.end());
            flat.steps.push_back(static_cast<std::size_t>(std::round(path.getControlDuration(i) / info_.planner.step)));
        }
        for (std::size_t i = 0; i < path.getStateCount(); ++i)
        {
            read(path.getState(i), a_);
            flat.states.insert(flat.states.end(), a_.begin(), a_.end());
        }
        return flat;
    }

    bridge::FinishedPath ModelHandle::finish(const FlatPath &found, bool solved,
                                             const bridge::FinishSettings &settings) const
    {
        return finisher_->finish(slice(found.controls), slice(found.steps), slice(found.states), solved, settings);
    }

    bridge::SearchStats summedSearchStats(const std::vector<ModelHandlePtr> &models)
    {
        bridge::SearchStats sum = bridge::search_stats(models.at(0)->propagator());
        for (std::size_t i = 1; i < models.size(); ++i)
            sum = bridge::add_search_stats(sum, bridge::search_stats(models[i]->propagator()));
        return sum;
    }
}  // namespace pushplan::detail
