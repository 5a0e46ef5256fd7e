#include "pushplan/cpp/problem/model_handle.h"

#include <stdexcept>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace pushplan::detail
{
    ModelHandle::ModelHandle(rust::Box<bridge::Problem> problem)
      : problem_(std::move(problem)),
        info_(std::make_shared<const bridge::SceneInfo>(problem_->info())),
        propagator_(bridge::Propagator::make(*problem_)),
        goal_(bridge::Goal::make(*problem_))
    {
    }

    void ModelHandle::setParticles(std::size_t count, std::uint64_t seed)
    {
        if (view_)
            throw std::logic_error("perturbed worlds must be set before the state space is made");
        problem_->set_particles(count, seed);
    }

    const std::shared_ptr<const StateView> &ModelHandle::view() const
    {
        if (!view_)
            view_ = std::make_shared<const StateView>(info_, problem_->start_particles().size(),
                                                      problem_->static_clutter());
        return view_;
    }

    void ModelHandle::writeStart(ob::State *state) const
    {
        view()->write(std::vector<double>(info_->start.begin(), info_->start.end()), state);
        const rust::Vec<double> start = problem_->start_particles();
        std::copy(start.begin(), start.end(), view()->particles(state).begin());
    }

    double ModelHandle::goalDistance(const ob::State *state) const
    {
        view()->read(state, a_);
        return goal_->distance(slice(a_), view()->particles(state));
    }

    bool ModelHandle::propagate(const ob::State *state, const oc::Control *control, std::size_t steps,
                                ob::State *result) const
    {
        const StateView &view = *this->view();
        view.read(state, a_);  // copies first: OMPL may pass state == result
        const rust::Slice<const double> from = view.particles(state);
        particles_.assign(from.begin(), from.end());
        view.readControl(control, control_);
        b_.resize(a_.size());
        const bool valid = propagator_->propagate(slice(a_), slice(particles_), slice(control_), steps,
                                                  rust::Slice<double>(b_.data(), b_.size()), view.particles(result));
        view.write(b_, result);
        return valid;
    }

    bridge::SearchStats summedSearchStats(const std::vector<ModelHandlePtr> &models)
    {
        bridge::SearchStats sum = bridge::search_stats(models.at(0)->propagator());
        for (std::size_t i = 1; i < models.size(); ++i)
            sum = bridge::add_search_stats(sum, bridge::search_stats(models[i]->propagator()));
        return sum;
    }
}  // namespace pushplan::detail
