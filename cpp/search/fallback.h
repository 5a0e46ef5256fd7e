// A fallback: a search that hands the problem to another search when, after a budget of
// propagation steps, no state it has reached has moved the goal object.
//
// Push KPIECE's controls push the goal object toward its goal, which needs the hand at
// the goal object first. Where the arm must swing round through clutter to get there
// (dense scene 17: in 20 s its goal object never moves), the guided pushes head the tool
// straight across the clutter and jam, while the paper's PC RRT, whose random joint-space
// targets sweep the arm's postures, gets there (BENCHMARKS.md, "Dense 17 and 19 over
// twelve seeds"). A search that has not once moved the goal object has nothing its
// guidance can build on; it goes on as the other search instead. A search that moves it,
// if only sideways, keeps going (in dense scenes 02 and 04 such searches get there a few
// seconds later; handing them over at 1 M steps cost 2-5 s: BENCHMARKS.md, "Push KPIECE
// falls back to PC RRT"). Counted in propagation steps, the handover happens at the same
// iteration whatever the timing.
//
// Whether the goal object has moved is read from goal distances: the model keeps the
// least and the largest it has met (lanes credit theirs), both the start's until a state
// moves the goal object.
//
// A first search on several threads (Push KPIECE on lanes) leaves them idle when it hands
// over to one PC RRT: on the 2-core machine dense 17 was searched at one thread's rate
// for the rest of the time. So the fallback is one independent PC RRT per thread, each on
// a model of its own (the search's, then its lanes'), in the lock-step rounds of a
// Portfolio: the first to reach the goal, lowest-numbered within a round, gives the plan,
// whatever the timing. Their steps and goal distances are credited to the search's model
// after each round, so its counts (progress, benchmark logs) are every thread's.
//
// The fallback's PC RRT is slow at the push itself, and Push KPIECE is fast at it once
// the hand is at the goal object. In dense 17, PC RRT's trees first moved the goal box
// after 6-24 s in five of eight runs (the others not within 30 s), and only two of those
// five solved within 30 s, 1-3 s later; from the state where each of five PC RRT paths
// first moved it, Push KPIECE solved in 0.3-5.4 s with each of three seeds
// (docs/notes/dense-clutter-and-push-kpiece.md). So the search hands the problem back: as
// soon as a fallback's tree holds a state that has moved the goal object nearer the goal
// than any state handed back before, Push KPIECE searches from that state for
// `patience_steps`; its path, after the fallback's path to that state, is the plan. Within
// that, it must bring the goal object nearer the goal than the state it started from, or
// the fallbacks go on with their trees as they were; if it does, it keeps the problem, as
// the first search does before the handover. Each fallback's own goal distances are read
// (the models' goal watch restarts after each search from a handed-back state), so the
// first search's states, met on the same models, never hand back.
#pragma once

#include "pushplan/cpp/problem/model_handle.h"
#include "pushplan/cpp/search/portfolio.h"
#include "pushplan/cpp/search/wrapped_search.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace pushplan::detail
{
    /// Runs `search`; when `patience_steps` propagation steps have gone by and every goal
    /// distance met is still the start state's, clears it (the closest path found stays
    /// in the problem definition) and runs the `fallbacks` from then on, each from the
    /// same start in a problem definition of its own (the first on `model`), on a thread
    /// each when there are several. The first to solve, or else the one closest to the
    /// goal, adds its path to the search's problem definition.
    /// clear() starts the running searches over: `search` before the handover (the goal
    /// distances met stay the model's), the fallbacks after it.
    class Fallback : public WrappedSearch
    {
    public:
        Fallback(ompl::base::PlannerPtr search, std::vector<Search> fallbacks, ModelHandlePtr model,
                 std::uint64_t patience_steps);

        ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
        void clear() override;
        void setup() override;
        void setProblemDefinition(const ompl::base::ProblemDefinitionPtr &pdef) override;
        /// The first search's tree, or once it has handed over every fallback's (and the
        /// first search's from the last state handed back, once it has).
        void getPlannerData(ompl::base::PlannerData &data) const override;

        /// The first search (search() is the one running).
        const ompl::base::PlannerPtr &wrapped() const override { return first_; }
        /// Whether the fallback has taken over.
        bool fellBack() const { return search_ == fallbacks_[0].planner; }
        /// How often the first search has run again from a state a fallback reached.
        std::uint64_t handedBack() const { return handed_back_; }
        /// The fallback's searches (the first runs on the model of this search).
        const Portfolio &fallbacks() const { return fallbacks_; }

    private:
        /// True once the patience is spent and no state has moved the goal object. Goal
        /// distances met only ever spread, so the first look past the patience decides:
        /// a search that has moved the goal object is kept, and not asked again.
        bool handOverDue();
        /// Runs the fallbacks (in rounds, on their threads, when there are several) and adds
        /// the best path among them to the problem definition.
        ompl::base::PlannerStatus solveWithFallbacks(const ompl::base::PlannerTerminationCondition &ptc);
        /// The lowest-numbered fallback whose tree holds a state nearer the goal than
        /// `handback_distance_`, if any (read from its goal's own closest distance).
        std::optional<std::size_t> nearerThanHandedBack() const;
        /// The first search from the end of fallback `i`'s closest path, for the patience
        /// or until `ptc`; adds the joined path to the problem definition if it solves
        /// (returns true then).
        bool searchFromFallback(std::size_t i, const ompl::base::PlannerTerminationCondition &ptc);
        /// Fallback `i`'s model's steps and seconds so far count as credited.
        void creditedUpToNow(std::size_t i);
        /// Credits the model with the fallbacks' steps, seconds and goal distances since
        /// the last call (the first fallback's model is the model itself).
        void creditFallbacks();

        ompl::base::PlannerPtr first_;
        Portfolio fallbacks_;
        /// Each fallback model's steps and seconds credited so far (the first's unused).
        std::vector<std::uint64_t> credited_steps_;
        std::vector<double> credited_seconds_;
        ModelHandlePtr model_;
        std::uint64_t patience_steps_;
        /// The model's step count when the current first search began.
        std::uint64_t began_at_ = 0;
        /// The start state's goal distance (m or rad), once solve() has run.
        std::optional<double> start_distance_;
        /// The first search has moved the goal object: it keeps the problem.
        bool kept_ = false;
        /// The goal distance of the last state handed back (the start's at first).
        double handback_distance_ = 0.0;
        std::uint64_t handed_back_ = 0;
    };

    /// Whether a planner is or wraps a Fallback that has handed over.
    bool fellBack(const ompl::base::PlannerPtr &planner);
    /// How often a planner that is or wraps a Fallback has handed the problem back to its
    /// first search (0 for any other planner).
    std::uint64_t handedBack(const ompl::base::PlannerPtr &planner);
}  // namespace pushplan::detail
