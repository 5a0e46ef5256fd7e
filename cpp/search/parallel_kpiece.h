// KPIECE1 on several threads: one search on every core.
//
// An iteration of KPIECE1 selects a motion from its grid, samples a control, propagates
// it, projects the states reached and measures their distance to the goal, and adds
// them to the grid. All but the selection and the adding need no tree, and they are
// nearly all of the time (for Push KPIECE in dense clutter, propagation alone is 55-60 %
// and sampling a push most of the rest). Here `lanes` iterations are in flight at once,
// iteration j on lane j mod lanes (a model and control sampler of its own), while the
// grid is touched by one thread at a time in a fixed order: iteration j joins the grid
// after j - 1, and the iteration that takes its lane next (j + lanes) is selected right
// after. So the tree, the random numbers and the plan depend on the seed and the number
// of lanes, never on thread timing or on how many threads run the lanes; with one lane
// the search is OMPL's KPIECE1 exactly (the same random numbers in the same order:
// tests/cpp/parallel_kpiece.cpp).
//
// Any thread takes any work that is ready: the next join, else the earliest lane
// waiting for its extension. With more lanes than threads a thread rarely waits: an
// extension's time varies tenfold (a push stopped after one step or run for fifty), and
// with one lane per thread each join waited for the slower of the two.
#pragma once

#include "pushplan/cpp/problem/model_handle.h"
#include "pushplan/cpp/search/tree_size.h"

#include <ompl/base/Goal.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pushplan::detail
{
    /// One thread's means to extend a tree: a model no other thread touches, with the
    /// space information (propagator, validity, control sampler), projection and goal of
    /// its own. The state space is the search's: lanes only allocate and copy states in
    /// it, which any thread may do at once (each OMPL state space is one more entry in a
    /// list OMPL walks whenever one is destroyed: docs/notes/any-arm.md, "Lanes on sixteen
    /// threads").
    struct Lane
    {
        ompl::control::SpaceInformationPtr si;
        ModelHandlePtr model;
        /// The search's projection, computed on this lane's model.
        ompl::base::ProjectionEvaluatorPtr projection;
        ompl::base::GoalPtr goal;
        /// The seed of the lane's random streams (its control sampler's).
        std::uint64_t seed = 0;
    };

    /// The lanes of one KPIECE search on `threads` (> 1) threads: threads plus spare lanes,
    /// so that a thread whose next join waits on another's long extension extends a spare
    /// lane meanwhile. More lanes keep the threads busier but make each selection blinder
    /// to the extensions in flight. The spares grow with the square of the threads, up to
    /// two per thread: the more threads, the more extensions finish while the head's runs
    /// (an extension's time varies tenfold). One spare on two threads (the best of 2-4
    /// lanes: docs/notes/dense-clutter-and-push-kpiece.md, "Lanes"); 32 on sixteen, where
    /// one spare left the threads idle half the time and 48 lanes solved the hard scenes
    /// fastest of 17, 32 and 48 (BENCHMARKS.md, "Sixteen cores"). Counts
    /// between are interpolated, not measured.
    constexpr unsigned lanesFor(unsigned threads)
    {
        const unsigned spares = threads * threads / 8;
        return threads + (spares < 1 ? 1 : spares > 2 * threads ? 2 * threads : spares);
    }

    /// The threads a search with `lanes` lanes was made for: the most whose lanesFor is at
    /// most `lanes` (at least one). What a search runs once per thread (the fallback's PC
    /// RRTs) is counted from its lanes with it, so that it depends on the lanes alone.
    constexpr unsigned threadsFor(std::size_t lanes)
    {
        unsigned threads = 1;
        while (lanesFor(threads + 1) <= lanes)
            ++threads;
        return threads;
    }

    class ParallelKPIECE : public ompl::control::KPIECE1, public TreeSize
    {
    public:
        /// `tree_model` is the model of `si`: its counts are credited with each lane's
        /// propagation steps and goal distances as their iterations join the tree, so a
        /// termination condition that counts steps sees the same count at the same
        /// iteration whatever the timing.
        /// `threads` threads run the lanes (0: one per lane).
        ParallelKPIECE(const ompl::control::SpaceInformationPtr &si, std::uint_fast32_t seed,
                       ModelHandlePtr tree_model, std::vector<Lane> lanes, unsigned threads = 0);

        ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
        /// Also drops the lanes' control samplers: the next solve() draws new ones, as
        /// KPIECE1 draws its own sampler anew.
        void clear() override;
        std::size_t treeSize() const override { return tree_.size; }

    private:
        struct Extension;

        /// Chooses the motion to extend (KPIECE1's selection); on the tree's turn.
        void select(Extension &e, CloseSamples &close_samples);
        /// Samples a control, propagates it, projects the states reached and measures the
        /// goal distance of each motion's end; on lane `lane`, no tree needed.
        void extend(Extension &e, std::size_t lane);
        /// Adds an extended iteration to the tree; true if it reached the goal. On the
        /// tree's turn.
        bool add(Extension &e, CloseSamples &close_samples);
        /// KPIECE1's addMotion at grid coordinates the lane computed already: the tree's
        /// turn, which no other thread can share, does not project states again.
        Grid::Cell *addMotionAt(Motion *motion, const Grid::Coord &coord, double distance);
        /// Added to the goal distance in a new cell's importance (KPIECE1's offset): no
        /// division by zero at the goal.
        static constexpr double kGoalDistanceOffset = 1e-3;

        ModelHandlePtr tree_model_;
        std::vector<Lane> lanes_;
        unsigned threads_;
        std::vector<ompl::control::ControlSamplerPtr> samplers_;  // one per lane
        /// Whether a selection updates its cell's importance at once (more than one lane):
        /// the selections in flight would otherwise all take the grid's top cell.
        bool update_on_select_ = false;

        // The best so far within one solve(): exact, else closest.
        Motion *solution_ = nullptr;
        Motion *approximate_ = nullptr;
        double approximate_distance_ = 0.0;
    };
}  // namespace pushplan::detail
