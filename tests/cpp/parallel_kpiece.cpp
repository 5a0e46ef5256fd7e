// ParallelKPIECE against OMPL's KPIECE1 (run by tests/integration/cpp_api.rs, built with the
// library's internal headers). With one propagation lane it must be KPIECE1 exactly:
// the same random numbers drawn in the same order, the same tree and the same path,
// bit for bit; OMPL's own implementation is the oracle. Each search runs until a budget
// of propagation steps, so the comparison does not depend on timing.
#include "pushplan/cpp/search/parallel_kpiece.h"
#include "pushplan/cpp/problem/problem.h"

#include <ompl/base/PlannerData.h>
#include <ompl/util/Console.h>

#include "expect.h"
#include "search_run.h"

#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

namespace
{
    namespace ob = ompl::base;
    namespace pd = pushplan::detail;
    using pushplan::PlannerKind;
    using test::expect;
    using test::failures;

    struct Search
    {
        bool exact = false;
        pd::FlatPath path;
        unsigned tree_states = 0;
        /// The planner's own count (TreeSize, for progress reports); -1 if it has none.
        long reported_states = -1;
        std::uint64_t steps = 0;
        /// Steps the lanes' own models took, joined to the tree or not.
        std::uint64_t lane_steps = 0;
    };

    /// One search of `kind` with `lanes` lanes (0: OMPL's KPIECE1) run by `threads`
    /// threads (0: one per lane), until it solves or has taken `budget` propagation steps.
    Search search(const std::string &scene, PlannerKind kind, std::uint64_t seed, unsigned lanes,
                  std::uint64_t budget, unsigned threads = 0)
    {
        const test::SearchRun run = test::runSearch(scene, kind, seed, lanes, threads, 0, 0, budget);
        const auto &[model, problem, extension_lanes, planner] = run;
        Search s;
        s.exact = problem.setup->haveExactSolutionPath();
        if (problem.setup->getProblemDefinition()->hasSolution())
            s.path = model->view()->readPath(problem.setup->getSolutionPath());
        ob::PlannerData data(problem.setup->getSpaceInformation());
        planner->getPlannerData(data);
        s.tree_states = data.numVertices();
        if (const auto *tree = dynamic_cast<const pd::TreeSize *>(planner.get()))
            s.reported_states = static_cast<long>(tree->treeSize());
        s.steps = model->propagationSteps();
        for (const pd::Lane &lane : extension_lanes)
            s.lane_steps += lane.model->propagationSteps();
        return s;
    }

    bool samePath(const Search &a, const Search &b)
    {
        return test::samePath(a.path, b.path);
    }
}  // namespace

int main()
{
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    const std::string scene = "scenes/herb_fig1_clutter.yaml";

    // Push KPIECE solves this scene from seed 2 within a few thousand steps.
    const Search ompl_push = search(scene, PlannerKind::PushKpiece, 2, 0, 400000);
    const Search one_lane_push = search(scene, PlannerKind::PushKpiece, 2, 1, 400000);
    std::cout << "  Push KPIECE: " << ompl_push.steps << " steps, " << ompl_push.tree_states << " states (OMPL), "
              << one_lane_push.steps << " steps, " << one_lane_push.tree_states << " states (one lane)\n";
    expect(ompl_push.exact && one_lane_push.exact, "both solve the scene");
    expect(samePath(ompl_push, one_lane_push), "one lane finds OMPL KPIECE1's path, bit for bit");
    expect(ompl_push.tree_states == one_lane_push.tree_states && ompl_push.steps == one_lane_push.steps,
           "with the same tree, after the same steps (the lane's steps counted on the search's model)");

    // KPIECE1 with OMPL's own control sampler, stopped by the budget before it solves:
    // the same tree and the same closest path.
    const Search ompl_plain = search(scene, PlannerKind::Kpiece, 5, 0, 30000);
    const Search one_lane_plain = search(scene, PlannerKind::Kpiece, 5, 1, 30000);
    std::cout << "  KPIECE1: " << ompl_plain.tree_states << " states (OMPL), " << one_lane_plain.tree_states
              << " states (one lane)\n";
    expect(ompl_plain.tree_states > 100 && ompl_plain.tree_states == one_lane_plain.tree_states &&
               samePath(ompl_plain, one_lane_plain),
           "unsolved within a budget: the same tree and the same closest path");

    // Two lanes: another search than KPIECE1's (each selection sees the tree without the
    // extension still in flight), the same one every time.
    const Search two = search(scene, PlannerKind::PushKpiece, 2, 2, 400000);
    const Search two_again = search(scene, PlannerKind::PushKpiece, 2, 2, 400000);
    expect(two.exact && samePath(two, two_again) && two.tree_states == two_again.tree_states &&
               two.steps == two_again.steps,
           "two lanes solve it the same way twice");

    // Four lanes: the search depends on the lanes, not on the threads that run them.
    const Search four = search(scene, PlannerKind::PushKpiece, 2, 4, 400000, 2);
    bool same_on_any_threads = four.exact;
    for (unsigned threads : {1u, 4u})
    {
        const Search other = search(scene, PlannerKind::PushKpiece, 2, 4, 400000, threads);
        same_on_any_threads = same_on_any_threads && samePath(four, other) &&
                              four.tree_states == other.tree_states && four.steps == other.steps &&
                              four.lane_steps == other.lane_steps;
    }
    // The lanes' own counts too: the iterations in flight when the search ends are
    // extended whichever thread gets there first (search statistics come from them).
    expect(same_on_any_threads && four.lane_steps > four.steps,
           "four lanes solve it the same way on one, two and four threads, extending the same iterations");

    // The lane rule and its inverse: one spare lane on two threads, two per thread on
    // sixteen, and the threads (what the fallback counts its searches by) found again from
    // the lanes for every count, the lanes growing with the threads.
    bool inverse = pd::lanesFor(2) == 3 && pd::lanesFor(16) == 48;
    for (unsigned threads = 1; threads <= 256; ++threads)
        inverse = inverse && pd::threadsFor(pd::lanesFor(threads)) == threads &&
                  pd::lanesFor(threads + 1) > pd::lanesFor(threads) && pd::lanesFor(threads) <= 3 * threads;
    expect(inverse, "threadsFor finds the thread count of every search's lanes");

    // The tree size progress reports show, against OMPL's planner data.
    bool counted = true;
    for (const Search *s : {&ompl_push, &one_lane_push, &ompl_plain, &one_lane_plain, &two})
        counted = counted && s->reported_states == static_cast<long>(s->tree_states);
    expect(counted, "each reports its tree's size as OMPL's planner data counts it");
    return failures == 0 ? 0 : 1;
}
