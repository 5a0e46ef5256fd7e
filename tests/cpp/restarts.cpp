// Restarting (run by tests/integration/cpp_api.rs, built with the library's internal headers): each
// attempt is announced once, in order, before it runs, and again from the first after
// clear(); Push KPIECE's grid has the goal object's cells of 2.5 cm in its first attempt
// and of 1.25 cm after, on the search's projection and on every lane's, so that a
// restarted search on two lanes is the same on one thread and on two. Budgets are
// counted in propagation steps, so nothing here depends on timing. The oracle for the
// attempts is Luby's sequence written out (attempts of 3 000 x 1, 1, 2, 1, 1, 2 steps
// start at 0, 3 000, 6 000, 12 000, 15 000 and 18 000), for the cells the numbers
// written out.
#include "pushplan/cpp/problem/problem.h"
#include "pushplan/cpp/search/restarts.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/util/Console.h>

#include "expect.h"
#include "search_run.h"

#include <cstdint>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace
{
    namespace ob = ompl::base;
    namespace pd = pushplan::detail;
    using pushplan::PlannerKind;
    using test::expect;

    constexpr std::uint64_t kSeed = 3;
    constexpr std::uint64_t kRestart = 3000;
    // Push KPIECE does not solve scene 22 within these budgets (it needs about a million
    // steps), so every attempt runs to its end.
    const std::string kScene = "scenes/benchmark/scene_22.yaml";

    /// Runs `planner` (set up on `model`'s problem) until the model has taken `budget`
    /// propagation steps in all.
    void runUntil(const ob::PlannerPtr &planner, const pd::ModelHandlePtr &model, std::uint64_t budget)
    {
        planner->solve(ob::PlannerTerminationCondition([&] { return model->propagationSteps() >= budget; }));
    }

    /// The cells of the grids a search's attempts use: the search's projection's, then
    /// each lane's.
    std::vector<std::vector<double>> gridCells(const test::SearchRun &run)
    {
        std::vector<std::vector<double>> cells{
            run.problem.setup->getStateSpace()->getDefaultProjection()->getCellSizes()};
        for (const pd::Lane &lane : run.lanes)
            cells.push_back(lane.si->getStateSpace()->getDefaultProjection()->getCellSizes());
        return cells;
    }

    bool allAre(const std::vector<std::vector<double>> &cells, const std::vector<double> &expected)
    {
        for (const std::vector<double> &c : cells)
            if (c != expected)
                return false;
        return true;
    }
}  // namespace

int main()
{
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

    // Attempts announced: Push KPIECE's bare search, restarted by hand with a recorder.
    {
        const pd::ModelHandlePtr model = test::load(kScene);
        const pd::Problem problem = pd::makeProblem(model, kSeed, model->info().planner.k);
        std::vector<std::uint64_t> announced;
        auto restarting = std::make_shared<pd::Restarting>(
            pd::makePlanner(PlannerKind::PushKpiece, problem, kSeed, 0.05, false, 0, 0, {}, 0), model, kRestart,
            [&announced](std::uint64_t attempt) { announced.push_back(attempt); });
        problem.setup->setPlanner(restarting);
        problem.setup->setup();
        runUntil(restarting, model, 20000);
        expect(announced == std::vector<std::uint64_t>{1, 2, 3, 4, 5, 6} && restarting->restarts() == 5,
               "within 20 000 steps, attempts 1-6 are each announced once, in order, before they run");
        restarting->clear();
        runUntil(restarting, model, 21000);
        expect(announced.size() == 7 && announced.back() == 1, "after clear(), the attempts start over from the first");
    }

    // Push KPIECE's grid in its first attempt and after, on the search and both lanes.
    const std::vector<double> first{0.05, 0.05, 0.025, 0.025, 0.05};
    const std::vector<double> later{0.05, 0.05, 0.0125, 0.0125, 0.05};
    const test::SearchRun in_first =
        test::runSearch(kScene, PlannerKind::PushKpiece, kSeed, 2, 2, kRestart, 0, kRestart - 1000);
    expect(allAre(gridCells(in_first), first) && gridCells(in_first).size() == 3,
           "in the first attempt, the goal object's cells are 2.5 cm on the search's grid and both lanes'");
    const test::SearchRun in_second =
        test::runSearch(kScene, PlannerKind::PushKpiece, kSeed, 2, 2, kRestart, 0, kRestart + 1000);
    expect(allAre(gridCells(in_second), later), "in the second, 1.25 cm on all three");

    // The same restarted search on one thread and on two: the lanes' grids change with
    // the search's.
    const auto sameSearch = [](const test::SearchRun &a, const test::SearchRun &b) {
        ob::PlannerData da(a.problem.setup->getSpaceInformation()), db(b.problem.setup->getSpaceInformation());
        a.planner->getPlannerData(da);
        b.planner->getPlannerData(db);
        return a.model->propagationSteps() == b.model->propagationSteps() && da.numVertices() == db.numVertices() &&
               pd::restartsOf(a.planner) == pd::restartsOf(b.planner);
    };
    const test::SearchRun one_thread = test::runSearch(kScene, PlannerKind::PushKpiece, kSeed, 2, 1, kRestart, 0, 20000);
    const test::SearchRun two_threads =
        test::runSearch(kScene, PlannerKind::PushKpiece, kSeed, 2, 2, kRestart, 0, 20000);
    std::cout << "  two lanes, 20 000 steps: " << pd::restartsOf(one_thread.planner) << " restarts\n";
    expect(pd::restartsOf(one_thread.planner) == 5 && sameSearch(one_thread, two_threads),
           "restarted on two lanes, the same steps, tree and restarts on one thread and on two");
    return test::failures == 0 ? 0 : 1;
}
