// Several independent searches of one problem, one per thread, advancing in lock-step
// rounds of a fixed number of propagation steps: which search finds the plan, and the
// plan, depend on the seeds and the number of searches, never on thread scheduling.
//
// A round ends inside each search's termination condition: the search pauses there,
// within one call of its planner's solve(), until every search has paused or returned.
// So a planner runs as if uninterrupted (OMPL's KPIECE1 keeps its goal-bias samples only
// within one call), and one search is the planner exactly, as `bench` measures it.
#pragma once

#include "pushplan/cpp/problem/problem.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace pushplan::detail
{
    /// One search: its own model, OMPL problem and planner.
    struct Search
    {
        Problem problem;
        ompl::base::PlannerPtr planner;
    };

    /// The seed of search `index` of a plan seeded with `seed`: search 0 keeps the plan's
    /// seed, so one search is the single-threaded planner exactly.
    std::uint64_t searchSeed(std::uint64_t seed, std::size_t index);

    class Portfolio
    {
    public:
        /// Propagation steps each search takes in a round, at the least: about 5 ms of
        /// work. A round ends when every search has taken its steps (or solved), so a
        /// search that solves waits for the rest of the round, and every search waits for
        /// the slowest. Short rounds bring an easy problem's plan at once; once a search
        /// has taken many steps, longer rounds keep it from waiting so often: a round is
        /// an eighth of the steps taken before it (kRoundGrowth), at most
        /// kLongestRoundSteps (BENCHMARKS.md, "Rounds that grow").
        static constexpr std::uint64_t kRoundSteps = 1000;
        /// The longest round: about 0.1 s of one thread's work in dense clutter, the most
        /// a solved search waits for the others.
        static constexpr std::uint64_t kLongestRoundSteps = 16000;
        /// A round is this fraction of the steps a search has taken before it: a plan
        /// found in it comes at most an eighth later, counted in steps.
        static constexpr std::uint64_t kRoundGrowth = 8;
        /// The steps of the round after `steps_taken` steps of a search.
        static std::uint64_t roundSteps(std::uint64_t steps_taken);

        /// `searches`, whose models cut a propagation at the time limit unless
        /// `iterations_run_whole` (PDST: `PlannerKind::cut_at_time_limit`). OMPL checks a
        /// search's termination condition only between its iterations, so such a search
        /// stops once the time left is shorter than its longest iteration so far: a PDST
        /// iteration re-propagates its cell's motions one step at a time, which took 0.1-0.45 s
        /// on a scene of 0.1 ms steps (tests/time_limit).
        Portfolio(std::vector<Search> searches, bool iterations_run_whole);

        /// Runs rounds until one ends with an exact solution or `out_of_time(0)` (asked from
        /// every thread) says stop, or every search's model is past its time limit; every
        /// search runs on a thread of its own, and `report`
        /// on the calling thread after a round when `report_due` says so, while every
        /// search is paused. A lone search keeps step with nobody: its rounds end only
        /// when a report is due (a pause wakes the calling thread, which, every 1 000
        /// steps, cost a lone search a few per cent: BENCHMARKS.md, "The tree's turn").
        /// Returns the lowest-numbered search holding an exact solution.
        /// `out_of_time(s)`: whether the time runs out within `s` seconds.
        std::optional<std::size_t> solve(const std::function<bool(double)> &out_of_time,
                                         const std::function<bool()> &report_due,
                                         const std::function<void()> &report);

        /// Drops search `i`'s tree and solutions: it starts over in the next round.
        void restart(std::size_t i);

        /// The search whose best path is best: exact, else closest to the goal (lowest
        /// number on ties); nullopt if none has a path.
        std::optional<std::size_t> best() const;

        std::size_t size() const { return searches_.size(); }
        const Search &operator[](std::size_t i) const { return searches_[i]; }

        /// Totals over the searches.
        std::uint64_t propagationSteps() const;
        double propagationSeconds() const;
        /// The smallest goal distance any search has reached.
        double closestGoalDistance() const;
        /// States in the searches' trees, for the planners that report it cheaply (RRT, KPIECE).
        std::optional<std::size_t> treeStates() const;
        /// Attempts started over for lack of a solution (Restarting), all searches.
        std::uint64_t restarts() const;
        /// Searches that handed over to their fallback (Fallback).
        std::uint64_t fallbacks() const;
        /// Times the searches that fell back handed the problem back (Fallback::handedBack).
        std::uint64_t handedBack() const;

    private:
        std::vector<Search> searches_;
        bool iterations_run_whole_;
    };
}  // namespace pushplan::detail
