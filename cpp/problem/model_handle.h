// The Rust model of one search: its problem, and the two parts whose state the search
// reports on (the propagator's counts, the goal's closest distance).
#pragma once

#include "pushplan/cpp/problem/state_view.h"
#include "pushplan/src/bridge.rs.h"
#include "rust/cxx.h"  // rust::Error

#include <ompl/base/State.h>
#include <ompl/control/Control.h>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace pushplan::detail
{
    /// Owns the Rust problem of one search (its scene, and the search it is set up for:
    /// Static RRT's pinned clutter, perturbed worlds), from which each OMPL class makes
    /// the part it uses (`bridge::ValidityChecker::make(model.problem())`, ...), and the
    /// parts whose state the search reports on, shared by the OMPL classes and the search
    /// wrappers: the propagator (propagation steps and time, the time limit) and the goal
    /// (the closest goal distance reached). Single-threaded, like the planners that use
    /// it (OMPL calls its const methods, hence the mutable scratch buffers).
    class ModelHandle
    {
    public:
        explicit ModelHandle(rust::Box<bridge::Problem> problem);

        const bridge::SceneInfo &info() const { return *info_; }
        /// The problem the parts are made from; its mode is set before the state space is
        /// made.
        bridge::Problem &problem() const { return *problem_; }

        /// Robust planning: every state carries `count` perturbed worlds drawn from `seed`
        /// (the model's ParticleWorlds). Only before the view is fixed.
        void setParticles(std::size_t count, std::uint64_t seed);
        /// The flat-state view of this problem's states, fixed from the first call on (the
        /// state space allocates by its layout).
        const std::shared_ptr<const StateView> &view() const;

        /// Writes the start state, with the perturbed worlds' start poses.
        void writeStart(ompl::base::State *state) const;
        /// Holds `control` for `steps` steps; writes the state reached; true if valid.
        bool propagate(const ompl::base::State *state, const ompl::control::Control *control,
                       std::size_t steps, ompl::base::State *result) const;
        /// The signed distance to the goal region (m or rad; negative inside).
        double goalDistance(const ompl::base::State *state) const;

        bridge::Propagator &propagator() const { return *propagator_; }
        const bridge::Goal &goal() const { return *goal_; }

        /// The propagation steps and seconds of this model's search: its own, and those a
        /// parallel search's lanes credited to it as their iterations joined its tree
        /// (ParallelKPIECE). What termination conditions and progress reports count.
        std::uint64_t propagationSteps() const { return propagator_->steps() + credited_steps_; }
        double propagationSeconds() const { return propagator_->seconds() + credited_seconds_; }
        void credit(std::uint64_t steps, double seconds)
        {
            credited_steps_ += steps;
            credited_seconds_ += seconds;
        }
        /// The smallest and the largest goal distance this model's search has met (m or
        /// rad), its own or credited by lanes.
        double closestGoalDistance() const { return std::min(goal_->closest_distance(), credited_closest_); }
        double farthestGoalDistance() const { return std::max(goal_->farthest_distance(), credited_farthest_); }
        void creditGoalDistance(double distance)
        {
            credited_closest_ = std::min(credited_closest_, distance);
            credited_farthest_ = std::max(credited_farthest_, distance);
        }
        /// From here on, the goal distances of this model's own states are read alone
        /// (`goal().closest_distance()`); those met before stay counted as credited, so
        /// closestGoalDistance() and farthestGoalDistance() do not change.
        void restartGoalWatch()
        {
            credited_closest_ = std::min(credited_closest_, goal_->closest_distance());
            credited_farthest_ = std::max(credited_farthest_, goal_->farthest_distance());
            goal_->forget_met();
        }

    private:
        mutable rust::Box<bridge::Problem> problem_;
        std::shared_ptr<const bridge::SceneInfo> info_;
        mutable rust::Box<bridge::Propagator> propagator_;
        rust::Box<bridge::Goal> goal_;
        /// Null until fixed.
        mutable std::shared_ptr<const StateView> view_;
        std::uint64_t credited_steps_ = 0;
        double credited_seconds_ = 0.0;
        double credited_closest_ = std::numeric_limits<double>::infinity();
        double credited_farthest_ = -std::numeric_limits<double>::infinity();
        mutable std::vector<double> a_, b_, control_, particles_;
    };

    using ModelHandlePtr = std::shared_ptr<ModelHandle>;

    /// The search statistics of `models` (a search's, with its lanes'), summed.
    bridge::SearchStats summedSearchStats(const std::vector<ModelHandlePtr> &models);
}  // namespace pushplan::detail
