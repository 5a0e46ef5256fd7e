#include "portfolio.h"

#include "restarts.h"

#include <algorithm>
#include <limits>

#include <exception>
#include <thread>

namespace ob = ompl::base;

namespace pushplan::detail
{
    std::uint64_t searchSeed(std::uint64_t seed, std::size_t index)
    {
        return index == 0 ? seed : subSeed(seed, 9000 + index);
    }

    Portfolio::Portfolio(std::vector<Search> searches) : searches_(std::move(searches))
    {
    }

    void Portfolio::advance(std::size_t i, const std::function<bool()> &out_of_time)
    {
        bridge::Model &model = searches_[i].problem.model->model();
        const std::uint64_t round_end = model.propagation_steps() + kRoundSteps;
        // Counted in steps, so the round ends at the same iteration whatever the timing.
        const ob::PlannerTerminationCondition round(
            [&] { return model.propagation_steps() >= round_end || out_of_time(); });
        // The solutions accumulate in the problem definition, the best first (OMPL keeps
        // exact before approximate, approximate by their distance to the goal).
        searches_[i].planner->solve(round);
    }

    std::optional<std::size_t> Portfolio::solve(const std::function<bool()> &out_of_time,
                                                const std::function<void()> &after_round)
    {
        const std::size_t n = searches_.size();
        for (;;)
        {
            // Search 0 on this thread, the others on threads of their own; a failure in any
            // is raised here after the round.
            std::vector<std::exception_ptr> failures(n);
            const auto run = [&](std::size_t i) {
                try
                {
                    advance(i, out_of_time);
                }
                catch (...)
                {
                    failures[i] = std::current_exception();
                }
            };
            std::vector<std::thread> threads;
            for (std::size_t i = 1; i < n; ++i)
                threads.emplace_back(run, i);
            run(0);
            for (std::thread &t : threads)
                t.join();
            for (const std::exception_ptr &failure : failures)
                if (failure)
                    std::rethrow_exception(failure);

            after_round();
            for (std::size_t i = 0; i < n; ++i)
                if (searches_[i].problem.setup->haveExactSolutionPath())
                    return i;
            if (out_of_time())
                return std::nullopt;
        }
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
            steps += s.problem.model->model().propagation_steps();
        return steps;
    }

    double Portfolio::propagationSeconds() const
    {
        double seconds = 0.0;
        for (const Search &s : searches_)
            seconds += s.problem.model->model().propagation_seconds();
        return seconds;
    }

    double Portfolio::closestGoalDistance() const
    {
        double closest = std::numeric_limits<double>::infinity();
        for (const Search &s : searches_)
            closest = std::min(closest, s.problem.model->model().closest_goal_distance());
        return closest;
    }

    std::uint64_t Portfolio::restarts() const
    {
        std::uint64_t restarts = 0;
        for (const Search &s : searches_)
            restarts += restartsOf(s.planner);
        return restarts;
    }

    std::optional<std::size_t> Portfolio::treeStates() const
    {
        std::size_t states = 0;
        for (const Search &s : searches_)
        {
            const auto *rrt = dynamic_cast<const SeededRRT *>(&innerPlanner(s.planner));
            if (rrt == nullptr)
                return std::nullopt;
            states += rrt->treeSize();
        }
        return states;
    }
}  // namespace pushplan::detail
