// The Rust model as the OMPL classes of one planning problem share it.
#pragma once

#include "pushplan/src/bridge.rs.h"
#include "rust/cxx.h"  // rust::Error
#include "pushplan/cpp/problem/state_layout.h"

#include <ompl/base/State.h>
#include <ompl/control/Control.h>
#include <ompl/control/PathControl.h>
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace pushplan::detail
{
    /// Owns the Rust model of one problem, its parts (one per OMPL concept: propagator,
    /// validity checker, metric, goal, projection, finisher, DARRT's primitives,
    /// grasping), and converts OMPL states and controls to the flat layouts of the
    /// bridge. Single-threaded, like the planners that use it (OMPL calls its const
    /// methods, hence the mutable scratch buffers).
    class ModelHandle
    {
    public:
        explicit ModelHandle(rust::Box<bridge::Problem> problem);

        const bridge::SceneInfo &info() const { return info_; }
        std::size_t stateSize() const { return flat().size(); }
        /// The bridge's flat layout of this scene's states.
        FlatLayout flat() const { return FlatLayout{info_.dof, info_.objects}; }
        std::size_t controlSize() const { return 3 + info_.dof; }

        /// Flat copy of an OMPL state of the pushplan state space.
        void read(const ompl::base::State *state, std::vector<double> &out) const;
        /// Writes a flat state into an OMPL state.
        void write(const std::vector<double> &in, ompl::base::State *state) const;
        void readControl(const ompl::control::Control *control, std::vector<double> &out) const;

        /// Robust planning: every state carries `count` perturbed worlds drawn from `seed`
        /// (the model's ParticleWorlds). Only before the state space fixes the layout.
        void setParticles(std::size_t count, std::uint64_t seed);
        /// The state layout, fixed from now on (the state space allocates by it).
        const StateLayout &fixLayout();
        /// Writes the start state, with the perturbed worlds' start poses.
        void writeStart(ompl::base::State *state) const;

        bool isValid(const ompl::base::State *state) const;
        double distance(const ompl::base::State *a, const ompl::base::State *b) const;
        double goalDistance(const ompl::base::State *state) const;
        /// Holds `control` for `steps` steps; writes the state reached; true if valid.
        bool propagate(const ompl::base::State *state, const ompl::control::Control *control,
                       std::size_t steps, ompl::base::State *result) const;

        /// In the Static RRT mode, puts every object except the goal object back at its
        /// start pose (a sample of that problem); otherwise leaves `flat` as it is.
        void pinClutter(std::vector<double> &flat) const;

        /// End-effector xy, goal-object xy and the blockage of the goal object's way (m):
        /// the projection-based planners' projection (the Rust model's `projection`).
        std::array<double, 5> project(const ompl::base::State *state) const;
        /// Which way the tool should move to push `object` toward `target` (world xy, m):
        /// unit xy in the world frame; none if the object is at the target.
        std::optional<std::array<double, 2>> pushHeading(const ompl::base::State *state, std::size_t object,
                                                         const std::array<double, 2> &target) const;
        /// The objects in the goal object's way, each with a place out of it.
        rust::Vec<bridge::PushTarget> pushBlockers(const ompl::base::State *state) const;

        /// A control path, flat: the controls one after another, their step counts, and
        /// the states at the start and after each control.
        struct FlatPath
        {
            std::vector<double> controls;
            std::vector<std::size_t> steps;
            std::vector<double> states;
        };
        FlatPath readPath(const ompl::control::PathControl &path) const;
        /// Finishes a found path the one way the model does (re-simulated, shortcut,
        /// robust: `planner::finish`).
        bridge::FinishedPath finish(const FlatPath &found, bool solved,
                                    const bridge::FinishSettings &settings) const;

        bridge::Problem &problem() const { return *problem_; }
        bridge::Propagator &propagator() const { return *propagator_; }
        const bridge::ValidityChecker &validityChecker() const { return *validity_; }
        const bridge::Metric &metric() const { return *metric_; }
        const bridge::Goal &goal() const { return *goal_; }
        const bridge::Finisher &finisher() const { return *finisher_; }
        const bridge::Darrt &darrt() const { return *darrt_; }
        const bridge::Grasping &grasping() const { return *grasping_; }

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

    private:
        /// The perturbed worlds' poses within a state's block (empty without worlds).
        rust::Slice<const double> particles(const ompl::base::State *state) const;
        rust::Slice<double> particles(ompl::base::State *state) const;

        mutable rust::Box<bridge::Problem> problem_;
        bridge::SceneInfo info_;
        mutable rust::Box<bridge::Propagator> propagator_;
        rust::Box<bridge::ValidityChecker> validity_;
        rust::Box<bridge::Metric> metric_;
        rust::Box<bridge::Goal> goal_;
        rust::Box<bridge::Projection> projection_;
        rust::Box<bridge::Finisher> finisher_;
        rust::Box<bridge::Darrt> darrt_;
        rust::Box<bridge::Grasping> grasping_;
        StateLayout layout_;
        bool layout_fixed_ = false;
        std::uint64_t credited_steps_ = 0;
        double credited_seconds_ = 0.0;
        double credited_closest_ = std::numeric_limits<double>::infinity();
        double credited_farthest_ = -std::numeric_limits<double>::infinity();
        mutable std::vector<double> a_, b_, control_, particles_;
    };

    using ModelHandlePtr = std::shared_ptr<ModelHandle>;

    /// The search statistics of `models` (a search's, with its lanes'), summed.
    bridge::SearchStats summedSearchStats(const std::vector<ModelHandlePtr> &models);

    inline rust::Slice<const double> slice(const std::vector<double> &v)
    {
        return rust::Slice<const double>(v.data(), v.size());
    }

    inline rust::Slice<const std::size_t> slice(const std::vector<std::size_t> &v)
    {
        return rust::Slice<const std::size_t>(v.data(), v.size());
    }

    inline rust::Slice<const std::int64_t> slice(const std::vector<std::int64_t> &v)
    {
        return rust::Slice<const std::int64_t>(v.data(), v.size());
    }
}  // namespace pushplan::detail
