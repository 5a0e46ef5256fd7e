#include "pushplan/cpp/search/portfolio.h"

#include "pushplan/cpp/search/fallback.h"
#include "pushplan/cpp/search/restarts.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace ob = ompl::base;

namespace pushplan::detail
{
    std::uint64_t searchSeed(std::uint64_t seed, std::size_t index)
    {
        return index == 0 ? seed : subSeed(seed, 9000 + index);
    }

    Portfolio::Portfolio(std::vector<Search> searches, bool iterations_run_whole)
      : searches_(std::move(searches)), iterations_run_whole_(iterations_run_whole)
    {
    }

    std::uint64_t Portfolio::roundSteps(std::uint64_t steps_taken)
    {
        return std::clamp(steps_taken / kRoundGrowth, kRoundSteps, kLongestRoundSteps);
    }

    namespace
    {
        /// Where the searches meet at the end of each round. A search pauses in `pause`
        /// (from its termination condition) or leaves for good in `leave` (its solve()
        /// returned); the coordinator waits in `await` until every search still running
        /// has paused, then `release`s them all to go on or to stop.
        class Rendezvous
        {
        public:
            explicit Rendezvous(std::size_t searches) : running_(searches) {}

            /// Blocks until the coordinator's decision; returns whether to stop.
            bool pause()
            {
                std::unique_lock<std::mutex> lock(mutex_);
                ++paused_;
                const std::uint64_t round = round_;
                changed_.notify_all();
                changed_.wait(lock, [&] { return round_ != round; });
                return stop_;
            }

            void leave()
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                --running_;
                changed_.notify_all();
            }

            /// Blocks until every running search has paused; returns how many still run.
            std::size_t await()
            {
                std::unique_lock<std::mutex> lock(mutex_);
                changed_.wait(lock, [&] { return paused_ == running_; });
                return running_;
            }

            void release(bool stop)
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                stop_ = stop;
                paused_ = 0;
                ++round_;
                changed_.notify_all();
            }

        private:
            std::mutex mutex_;
            std::condition_variable changed_;
            std::size_t running_;
            std::size_t paused_ = 0;
            std::uint64_t round_ = 0;
            bool stop_ = false;
        };
    }  // namespace

    std::optional<std::size_t> Portfolio::solve(const std::function<bool(double)> &out_of_time,
                                                const std::function<bool()> &report_due,
                                                const std::function<void()> &report)
    {
        const std::size_t n = searches_.size();
        const bool alone = n == 1;
        Rendezvous rendezvous(n);
        std::vector<std::exception_ptr> failures(n);
        const auto run = [&](std::size_t i) {
            const ModelHandle &model = *searches_[i].problem.model;
            // Rounds are counted in steps, so each ends at the same iteration whatever the
            // timing; the search pauses there without leaving solve(). A lone search's
            // timing cannot change its plan: it pauses only for a report. The steps are
            // the search's own, not those credited to its model between rounds (Fallback).
            // Past its model's time limit a search takes no more steps, so its round would
            // never end: it stops there.
            const auto steps = [&] { return model.propagator().steps(); };
            const std::uint64_t first_step = steps();
            std::uint64_t round_end = first_step + kRoundSteps;
            bool stopped = false;
            // The longest time between two checks outside a pause (s), where iterations run
            // whole: the time the next iteration may take past the limit.
            using Clock = std::chrono::steady_clock;
            Clock::time_point last_check = Clock::now();
            double longest_iteration = 0.0;
            const ob::PlannerTerminationCondition ptc([&] {
                if (iterations_run_whole_)
                {
                    const Clock::time_point now = Clock::now();
                    const double gap = std::chrono::duration<double>(now - last_check).count();
                    longest_iteration = std::max(longest_iteration, gap);
                    last_check = now;
                }
                if (stopped || out_of_time(longest_iteration) || model.propagator().past_time_limit())
                    return true;
                if (alone ? !report_due() : steps() < round_end)
                    return false;
                round_end += roundSteps(round_end - first_step);
                stopped = rendezvous.pause();
                last_check = Clock::now();
                return stopped;
            });
            try
            {
                // The solutions accumulate in the problem definition, the best first (OMPL
                // keeps exact before approximate, approximate by their distance to the goal).
                searches_[i].planner->solve(ptc);
            }
            catch (...)
            {
                failures[i] = std::current_exception();
            }
            rendezvous.leave();
        };
        std::vector<std::thread> threads;
        for (std::size_t i = 0; i < n; ++i)
            threads.emplace_back(run, i);

        const auto first_solved = [&]() -> std::optional<std::size_t> {
            for (std::size_t i = 0; i < n; ++i)
                if (searches_[i].problem.setup->haveExactSolutionPath())
                    return i;
            return std::nullopt;
        };
        const auto failed = [&] {
            return std::any_of(failures.begin(), failures.end(), [](const std::exception_ptr &f) { return bool(f); });
        };
        // A report that throws (an application's callback) stops the searches; its exception
        // leaves once they are joined (a joinable thread destroyed would terminate).
        std::exception_ptr report_failure;
        for (;;)
        {
            const std::size_t running = rendezvous.await();
            if (report_due())
            {
                try
                {
                    report();
                }
                catch (...)
                {
                    report_failure = std::current_exception();
                }
            }
            const bool stop = report_failure || running == 0 || first_solved() || failed() || out_of_time(0.0);
            rendezvous.release(stop);
            if (stop)
                break;
        }
        for (std::thread &t : threads)
            t.join();
        if (report_failure)
            std::rethrow_exception(report_failure);
        for (const std::exception_ptr &failure : failures)
            if (failure)
                std::rethrow_exception(failure);
        return first_solved();
    }

    void Portfolio::restart(std::size_t i)
    {
        searches_[i].problem.setup->getProblemDefinition()->clearSolutionPaths();
        searches_[i].planner->clear();
    }

    std::optional<std::size_t> Portfolio::best() const
    {
        std::optional<std::size_t> best;
        double best_difference = 0.0;
        for (std::size_t i = 0; i < searches_.size(); ++i)
        {
            const ob::ProblemDefinitionPtr &pdef = searches_[i].problem.setup->getProblemDefinition();
            if (!pdef->hasSolution())
                continue;
            if (pdef->hasExactSolution())
                return i;
            const double difference = pdef->getSolutionDifference();
            if (!best || difference < best_difference)
                best = i, best_difference = difference;
        }
        return best;
    }

    std::uint64_t Portfolio::propagationSteps() const
    {
        std::uint64_t steps = 0;
        for (const Search &s : searches_)
            steps += s.problem.model->propagationSteps();
        return steps;
    }

    double Portfolio::propagationSeconds() const
    {
        double seconds = 0.0;
        for (const Search &s : searches_)
            seconds += s.problem.model->propagationSeconds();
        return seconds;
    }

    double Portfolio::closestGoalDistance() const
    {
        double closest = std::numeric_limits<double>::infinity();
        for (const Search &s : searches_)
            closest = std::min(closest, s.problem.model->closestGoalDistance());
        return closest;
    }

    std::uint64_t Portfolio::restarts() const
    {
        std::uint64_t restarts = 0;
        for (const Search &s : searches_)
            restarts += restartsOf(s.planner);
        return restarts;
    }

    std::uint64_t Portfolio::fallbacks() const
    {
        std::uint64_t count = 0;
        for (const Search &s : searches_)
            count += fellBack(s.planner) ? 1 : 0;
        return count;
    }

    std::uint64_t Portfolio::handedBack() const
    {
        std::uint64_t count = 0;
        for (const Search &s : searches_)
            count += pushplan::detail::handedBack(s.planner);
        return count;
    }

    std::optional<std::size_t> Portfolio::treeStates() const
    {
        // The tree a planner grows, if it tells its size.
        const auto tree_of = [](const ob::PlannerPtr &planner) -> std::optional<std::size_t> {
            const auto *tree = dynamic_cast<const TreeSize *>(&innerPlanner(planner));
            return tree != nullptr ? std::optional<std::size_t>(tree->treeSize()) : std::nullopt;
        };
        std::size_t states = 0;
        for (const Search &s : searches_)
        {
            std::optional<std::size_t> searched;
            // A search that fell back searches on in its fallback's trees, all of them, and,
            // once it has handed back, in its first search's tree from the state handed back.
            if (const Fallback *fallback = wrapperOf<Fallback>(s.planner); fallback != nullptr && fallback->fellBack())
            {
                searched = fallback->fallbacks().treeStates();
                if (searched && fallback->handedBack() > 0)
                {
                    const std::optional<std::size_t> first = tree_of(fallback->wrapped());
                    searched = first ? std::optional<std::size_t>(*searched + *first) : std::nullopt;
                }
            }
            else
                searched = tree_of(s.planner);
            if (!searched)
                return std::nullopt;
            states += *searched;
        }
        return states;
    }
}  // namespace pushplan::detail
