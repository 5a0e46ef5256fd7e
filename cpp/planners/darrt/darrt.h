// The DARRT baseline (the whole-arm paper, Sec. V-A): an RRT over the same state space
// whose extensions are motion primitives instead of physics-propagated controls.
#pragma once

#include "pushplan/cpp/problem/arm_space.h"
#include "pushplan/cpp/problem/model_handle.h"

#include <ompl/base/Planner.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/control/PathControl.h>
#include <ompl/control/SpaceInformation.h>
#include <ompl/util/RandomNumbers.h>
#include <ompl/datastructures/NearestNeighborsGNATNoThreadSafety.h>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace pushplan::detail
{
    /// A DARRT solution: states joined by Transit motions and Push steps, checked by the
    /// model. Its controls are placeholders (zero, one propagation step each) because a
    /// caged object follows the hand by assumption, not by the pushing model: `check()`
    /// checks the primitives, and `length()` is the time at the joints' velocity limits.
    class PrimitivePath : public ompl::control::PathControl
    {
    public:
        /// `states` (flat, one after another) must have been checked: `report.valid`.
        /// `held[k]` is what the hand holds in state k (an object index, or -1).
        PrimitivePath(const ompl::control::SpaceInformationPtr &si, const ModelHandle &model,
                      const std::vector<double> &states, const std::vector<std::int64_t> &held,
                      bridge::PrimitiveCheck report);
        double length() const override;
        bool check() const override;
        const bridge::PrimitiveCheck &report() const { return report_; }

    private:
        rust::Box<bridge::Darrt> darrt_;
        std::vector<double> flat_;
        std::vector<std::int64_t> held_;
        bridge::PrimitiveCheck report_;
    };

    /// RRTTransit: OMPL's geometric RRT-Connect in the arm's joint space, every movable
    /// object an obstacle where it is, motions checked as Transit lines by the model.
    class ArmTransit
    {
    public:
        ArmTransit(const ModelHandle &model, double time_cap);
        /// Plans from `from` to the configuration of `to` (same objects); appends the
        /// waypoints after `from` (the last is `to`) to `motion`. Stops at `ptc` or the
        /// time cap.
        bool plan(const FlatState &from, const FlatState &to, const ompl::base::PlannerTerminationCondition &ptc,
                  std::uint_fast32_t seed, std::vector<FlatState> &motion);
        void setTimeCap(double seconds) { time_cap_ = seconds; }
        double timeCap() const { return time_cap_; }

    private:
        ArmSpace space_;
        double time_cap_;
    };

    /// DARRT with three primitives (Transit, RRTTransit, Push), and optionally a fourth,
    /// PickPlace (the paper's suggestion). Each iteration samples, with equal probability,
    /// a new arm configuration, a new pose of the goal object or a new pose of one other
    /// object, extends the nearest tree node towards it with the primitives, and stops
    /// when a node satisfies the goal.
    class Darrt : public ompl::base::Planner
    {
    public:
        /// DARRT on `model`'s problem (its primitives, validity checker and state view);
        /// `model` is kept for the paths it returns.
        Darrt(const ompl::control::SpaceInformationPtr &si, ModelHandlePtr model, std::uint_fast32_t seed);
        ~Darrt() override;

        ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
        void clear() override;
        void getPlannerData(ompl::base::PlannerData &data) const override;

        void reseed(std::uint_fast32_t seed);
        /// Probability that a goal-object sample is drawn from the goal disc.
        void setGoalBias(double bias) { goal_bias_ = bias; }
        double getGoalBias() const { return goal_bias_; }
        /// RRTTransit's time cap (s); the paper's is 15 s.
        void setTransitTime(double seconds) { transit_.setTimeCap(seconds); }
        double getTransitTime() const { return transit_.timeCap(); }
        /// Probability that a new object pose is reached by PickPlace (grasp, carry, set
        /// down) rather than Push; an object without grasps is pushed. 0: DARRT as in the
        /// paper.
        void setPickPlace(double probability) { pick_place_ = probability; }
        double getPickPlace() const { return pick_place_; }

    private:
        struct Node
        {
            FlatState state;
            ompl::base::State *ompl_state;
            int parent;
            /// The states after the parent's, ending with this node's.
            std::vector<FlatState> motion;
            /// What the hand holds in each of them (an object index, or -1).
            std::vector<std::int64_t> held;
        };

        /// `held` empty: the hand holds nothing along the motion.
        int addNode(int parent, std::vector<FlatState> motion, std::vector<std::int64_t> held = {});
        /// A new arm configuration: Transit, else RRTTransit. Returns the new node or -1.
        int extendArm(const ompl::base::PlannerTerminationCondition &ptc);
        /// A new pose of `object`: PickPlace (with probability pick_place_), else RRTTransit
        /// to the hand's place at it, then Push.
        int extendObject(int object, const ompl::base::PlannerTerminationCondition &ptc);
        /// PickPlace of `object` from node `from` to `target`; the new node or -1.
        int pickPlace(int from, int object, const std::array<double, 3> &target);
        /// RRTTransit from node `from` to `to` (same objects); appends the waypoints.
        bool rrtTransit(int from, const FlatState &to, const ompl::base::PlannerTerminationCondition &ptc,
                        std::vector<FlatState> &motion);
        ompl::base::PlannerStatus report(int goal_node);
        /// The node whose arm configuration is nearest `q` (joint space, Euclidean).
        int nearestArm(const FlatState &q) const;
        /// The node whose copy of `object` is nearest `xy` (centre distance), one drawn
        /// uniformly among the nodes that share the nearest place.
        int nearestObject(int object, const std::array<double, 2> &xy);
        /// Is the tree state `state` in the goal region (the problem definition's goal)?
        bool reachesGoal(const ompl::base::State *state) const;

        ModelHandlePtr model_;
        std::shared_ptr<const StateView> view_;
        rust::Box<bridge::Darrt> darrt_;
        rust::Box<bridge::ValidityChecker> validity_;
        ArmTransit transit_;
        ompl::RNG rng_;
        double goal_bias_;
        double pick_place_ = 0.0;
        std::vector<Node> nodes_;
        std::uint64_t transit_calls_ = 0;

        /// The tree's nodes by arm configuration (OMPL's GNAT; -1 stands for the query).
        ompl::NearestNeighborsGNATNoThreadSafety<int> arms_;
        mutable FlatState arm_query_;

        /// The distinct places (x, y) one object takes in the tree's nodes, in OMPL's GNAT.
        /// Most nodes share an object's place (every arm motion keeps it), so the structure
        /// holds places, each with its nodes in the order they joined the tree.
        struct ObjectPlaces
        {
            std::vector<std::array<double, 2>> xy;  ///< place id -> (x, y), m, world frame
            std::vector<std::vector<int>> nodes;    ///< place id -> nodes there
            std::map<std::array<double, 2>, int> id;
            ompl::NearestNeighborsGNATNoThreadSafety<int> tree;  ///< place ids; -1: the query
            std::array<double, 2> query{};
        };
        /// One per object.
        std::vector<std::unique_ptr<ObjectPlaces>> places_;
    };
}  // namespace pushplan::detail
