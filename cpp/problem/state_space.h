// The state space X = C_R x SE(2)^M of the paper (Sec. II-A) and its state sampler
// (Sec. III-B).
#pragma once

#include "pushplan/cpp/problem/model_handle.h"
#include "pushplan/cpp/problem/state_layout.h"

#include <ompl/base/StateSampler.h>
#include <ompl/base/StateSpace.h>
#include <ompl/util/RandomNumbers.h>

namespace pushplan::detail
{
    /// Joints (RealVector, joint-limit bounds) x one SE2 per movable object (table
    /// bounds). Its distance is the model's weighted metric.
    ///
    /// A state and all its components are allocated as one block: nearest-neighbour
    /// queries read thousands of states, and a compound of SE2 states is otherwise about
    /// twenty scattered heap objects (measured: half of planning time in cache misses).
    /// Within the block the numbers come last and together (StateLayout), so a distance
    /// reads few cache lines.
    class PushStateSpace : public ompl::base::CompoundStateSpace
    {
    public:
        /// The state space of `model`'s problem: fixes its state view, and measures
        /// distances with a metric of its own.
        explicit PushStateSpace(const ModelHandle &model);
        double distance(const ompl::base::State *a, const ompl::base::State *b) const override;
        /// The model metric's largest distance within the bounds.
        double getMaximumExtent() const override;
        ompl::base::State *allocState() const override;
        void freeState(ompl::base::State *state) const override;

        /// Copies the perturbed worlds' poses too (robust planning).
        void copyState(ompl::base::State *destination, const ompl::base::State *source) const override;
        /// The flat-state view of the space's states.
        const std::shared_ptr<const StateView> &view() const { return view_; }

    private:
        std::shared_ptr<const StateView> view_;
        rust::Box<bridge::Metric> metric_;
        StateLayout layout_;
        mutable std::vector<double> a_, b_;
    };

    /// Samples the robot and every object uniformly (joint limits, table extent, any
    /// yaw), valid or not; in Static RRT's problem the clutter stays where it starts.
    class PushStateSampler : public ompl::base::StateSampler
    {
    public:
        PushStateSampler(const PushStateSpace *space, std::uint_fast32_t seed);
        void sampleUniform(ompl::base::State *state) override;
        /// Not used by the control planners: uniform as well.
        void sampleUniformNear(ompl::base::State *state, const ompl::base::State *near, double distance) override;
        void sampleGaussian(ompl::base::State *state, const ompl::base::State *mean, double stdDev) override;

        /// One uniform sample (not checked): robot and objects; `fixed_object` (if >= 0)
        /// is left to the caller.
        static void sampleRaw(const bridge::SceneInfo &info, ompl::RNG &rng, std::vector<double> &out);

    private:
        std::shared_ptr<const StateView> view_;
        std::vector<double> buffer_;
    };
}  // namespace pushplan::detail
