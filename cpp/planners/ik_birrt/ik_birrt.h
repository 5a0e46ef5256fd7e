// IK-BiRRT (the manipulation-planning lecture; Berenson, Srinivasa, Ferguson, Collet,
// Kuffner 2009): a bidirectional RRT in the arm's joint space whose backward tree is
// rooted at inverse-kinematics solutions of Workspace Goal Regions.
#pragma once

#include "pushplan/cpp/problem/arm_space.h"
#include "pushplan/cpp/problem/model_handle.h"

#include <ompl/base/Planner.h>
#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/datastructures/NearestNeighbors.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace pushplan::detail
{
    /// "Reach a grasp of this object": the object's grasp regions at its pose in the arm
    /// space's context, sampled through inverse kinematics (the model's grasp_sample) and
    /// measured by the lecture's distance d(q, WGR).
    class GraspGoal : public ompl::base::GoalSampleableRegion
    {
    public:
        /// `from`: the full state the reach starts from (objects where they stay; its
        /// configuration seeds the inverse kinematics).
        GraspGoal(const ArmSpace &space, const ModelHandle &model, const FlatState &from, std::size_t object,
                  std::uint64_t seed);
        /// One try (a region, a displacement, inverse kinematics): false if it found no
        /// valid configuration.
        bool trySample(ompl::base::State *state) const;
        /// Tries until a sample is found; throws after 10 000 failed tries.
        void sampleGoal(ompl::base::State *state) const override;
        unsigned int maxSampleCount() const override;
        double distanceGoal(const ompl::base::State *state) const override;

    private:
        const ArmSpace &space_;
        rust::Box<bridge::Grasping> grasping_;
        FlatState from_;
        std::size_t object_;
        mutable std::uint64_t seed_;
        mutable FlatState scratch_;
    };

    /// The lecture's IKBiRRT: each iteration either (with probability P_sample, or when
    /// the goal tree is empty) adds IK solutions of the goal's regions to the goal tree as
    /// new roots, or samples a configuration, grows tree A toward it, grows tree B toward
    /// what A reached, and swaps the trees. Growing is RRT-Connect's: steps of at most
    /// `range` until the target is reached or a motion is invalid. The trees meet when B
    /// reaches A's new state. The goal must be a GraspGoal (or another sampleable region).
    class IkBiRrt : public ompl::base::Planner
    {
    public:
        IkBiRrt(const ompl::base::SpaceInformationPtr &si, std::uint_fast32_t seed);
        ~IkBiRrt() override;

        ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
        void clear() override;
        void setup() override;

        /// P_sample: probability of an iteration adding goal samples.
        void setSampleProbability(double p) { p_sample_ = p; }
        double getSampleProbability() const { return p_sample_; }
        /// Longest motion added at once (joint-space distance; 0: OMPL's default, a fifth
        /// of the space's extent).
        void setRange(double range) { range_ = range; }
        double getRange() const { return range_; }
        /// IK solutions in the goal tree.
        std::size_t goalSamples() const { return goal_samples_; }
        /// States in both trees.
        std::size_t treeSize() const;

    private:
        struct Motion
        {
            ompl::base::State *state = nullptr;
            Motion *parent = nullptr;
        };
        using Tree = std::shared_ptr<ompl::NearestNeighbors<Motion *>>;
        enum class Growth
        {
            Trapped,
            Advanced,
            Reached
        };

        Motion *add(Tree &tree, ompl::base::State *state, Motion *parent);
        /// Grows `tree` toward `target` until it is reached or a motion is invalid; `last`
        /// is the last state added (or the nearest, if none was).
        Growth grow(Tree &tree, const ompl::base::State *target, Motion *&last);
        void freeMotions();

        ompl::base::StateSamplerPtr sampler_;
        Tree start_tree_, goal_tree_;
        std::vector<Motion *> motions_;
        ompl::RNG rng_;
        double p_sample_ = 0.1;
        double range_ = 0.0;
        std::size_t goal_samples_ = 0;
    };
}  // namespace pushplan::detail
