// The OMPL problem of Alg. 1 for one scene, shared by the planner API and the benchmark.
#pragma once

#include "pushplan/cpp/problem/model_handle.h"
#include "pushplan/cpp/search/parallel_kpiece.h"
#include "pushplan/pushplan.h"
#include "pushplan/cpp/problem/state_space.h"

#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/control/SimpleSetup.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/rrt/RRT.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pushplan::detail
{
    /// Independent 32-bit seeds for the random sources of one plan.
    std::uint_fast32_t subSeed(std::uint64_t seed, std::uint64_t stream);

    /// One of OMPL's control planners (RRT, KPIECE1, EST, PDST, SST) whose own random
    /// numbers come from a given seed: OMPL would draw it from its process-wide generator,
    /// and a plan would depend on what the process made before.
    template <class OmplPlanner>
    class Seeded : public OmplPlanner
    {
    public:
        Seeded(const ompl::control::SpaceInformationPtr &si, std::uint_fast32_t seed) : OmplPlanner(si)
        {
            this->rng_.setLocalSeed(seed);
        }
    };

    /// Seeded oc::RRT (its random numbers: the goal bias) whose nearest neighbours are the
    /// model's (ModelNearestNeighbors).
    class SeededRRT : public Seeded<ompl::control::RRT>, public TreeSize
    {
    public:
        SeededRRT(const ompl::control::SpaceInformationPtr &si, const ModelHandle &model, std::uint_fast32_t seed,
                  const std::string &name);
        std::size_t treeSize() const override { return nn_ ? nn_->size() : 0; }
    };

    /// Seeded oc::KPIECE1 (one lane: OMPL's class itself) that says how big its tree is.
    class SeededKPIECE : public Seeded<ompl::control::KPIECE1>, public TreeSize
    {
    public:
        using Seeded<ompl::control::KPIECE1>::Seeded;
        std::size_t treeSize() const override { return tree_.size; }
    };

    /// Projection for OMPL's projection-based planners (KPIECE1, Push KPIECE, EST, PDST):
    /// the end-effector's xy, the goal object's xy and the blockage of the goal object's
    /// way (m; ModelHandle::project), cells of 5 cm (Push KPIECE's: pushKpieceCellSizes).
    class PushProjection : public ompl::base::ProjectionEvaluator
    {
    public:
        /// Push KPIECE's cells in attempt `attempt` (from 1) of its restarted search: the
        /// goal object's xy in cells of 2.5 cm in the first attempt and of 1.25 cm in every
        /// later one, the rest 5 cm. A small move of the goal object is a new cell, which
        /// KPIECE's exploration of new cells goes on from (BENCHMARKS.md, "Finer cells for
        /// the goal object"). Most scenes are solved within the first attempt, where the
        /// finer cells cost time; the scenes that need restarts are those where the goal
        /// object's small moves matter (BENCHMARKS.md, "Finer cells after the first attempt").
        static std::vector<double> pushKpieceCellSizes(std::uint64_t attempt);

        /// The projection of `model`'s problem (a part of its own).
        PushProjection(const ompl::base::StateSpace *space, const ModelHandle &model);
        unsigned int getDimension() const override;
        void defaultCellSizes() override;
        void project(const ompl::base::State *state, Eigen::Ref<Eigen::VectorXd> projection) const override;

    private:
        std::shared_ptr<const StateView> view_;
        rust::Box<bridge::Projection> projection_;
        mutable std::vector<double> buffer_;
    };

    /// Spaces, samplers, propagator, validity checker, start and goal of one scene.
    struct Problem
    {
        ModelHandlePtr model;
        std::shared_ptr<PushStateSpace> space;
        std::shared_ptr<ompl::control::SimpleSetup> setup;
        /// Control samples per extension (Alg. 1's k).
        unsigned k = 1;
    };

    /// Sets up the problem: k is the number of control samples per extension (Alg. 1).
    Problem makeProblem(ModelHandlePtr model, std::uint64_t seed, unsigned k);

    /// Lane `index` of the search `search` seeded with `search_seed` (ParallelKPIECE), on
    /// `model`, in the search's state space.
    Lane makeLane(const Problem &search, ModelHandlePtr model, std::uint64_t search_seed, std::size_t index);

    /// A planner of the problem. Static RRT is the same RRT as PC RRT; the model decides
    /// that the clutter is static (ModelHandle's static-clutter mode). With restart_steps
    /// > 0 the search starts over when an attempt finds no solution (Restarting). With
    /// fallback_steps > 0 (Push KPIECE only; others throw) it hands over to PC RRT when
    /// that many steps have not moved the goal object (Fallback): as many independent PC
    /// RRT searches as the first search had threads (threadsFor its lanes; one without
    /// lanes). With lanes (the KPIECE planners only) the search extends on them
    /// (ParallelKPIECE), run by `threads` threads (0: one per lane); the search depends on
    /// the lanes, not on the threads.
    ompl::base::PlannerPtr makePlanner(PlannerKind kind, const Problem &problem, std::uint64_t seed,
                                       double goal_bias, bool intermediate_states, std::uint64_t restart_steps,
                                       std::uint64_t fallback_steps, std::vector<Lane> lanes = {},
                                       unsigned threads = 0);
}  // namespace pushplan::detail
