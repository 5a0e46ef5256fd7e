// Fallback (run by tests/integration/cpp_api.rs, built with the library's internal headers): Push
// KPIECE hands over to PC RRT exactly when its patience is spent and no state has moved
// the goal object, and changes nothing otherwise. The oracle for "moved" is the first
// search's own tree, run alone for the patience: the goal object's pose in each vertex
// (OMPL's planner data) against its pose at the start; the Fallback reads goal distances.
// Once PC RRT's tree has moved the goal object nearer the goal, Push KPIECE searches on
// from that state; the joined plan is checked by propagating its controls from the start
// with a model of its own, and its first part against PC RRT's tree.
#include "pushplan/cpp/search/fallback.h"
#include "pushplan/cpp/problem/problem.h"
#include "pushplan/cpp/search/restarts.h"

#include <ompl/base/PlannerData.h>
#include <ompl/util/Console.h>

#include "expect.h"
#include "search_run.h"

#include <algorithm>
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

    constexpr std::uint64_t kSeed = 3;

    struct Search
    {
        bool fell_back = false;
        std::uint64_t handed_back = 0;
        bool solved = false;
        bool pc_rrt_tree = false;
        std::uint64_t restarts = 0;
        std::uint64_t steps = 0;
        /// Steps propagated on the search's own model (the rest credited by lanes, or by
        /// the fallback's other searches).
        std::uint64_t own_steps = 0;
        unsigned tree_states = 0;
        /// Tree vertices whose goal object stands elsewhere than at the start.
        unsigned goal_object_moved = 0;
        /// The vertices of the fallback's PC RRT trees, once it has handed over (flat states).
        std::vector<std::vector<double>> pc_rrt_vertices;
        pd::FlatPath path;
    };

    /// Push KPIECE on `scene` with the given patience (0: no fallback) and restart base,
    /// on `lanes` lanes (0: OMPL's KPIECE1) and `threads` threads, for `budget` steps.
    Search search(const std::string &scene, std::uint64_t patience, std::uint64_t restart, std::uint64_t budget,
                  unsigned lanes = 0, unsigned threads = 0)
    {
        const test::SearchRun run =
            test::runSearch(scene, PlannerKind::PushKpiece, kSeed, lanes, threads, restart, patience, budget);
        const pd::ModelHandlePtr &model = run.model;
        const pd::Problem &problem = run.problem;
        const ob::PlannerPtr &planner = run.planner;
        Search s;
        s.fell_back = pd::fellBack(planner);
        s.handed_back = pd::handedBack(planner);
        s.solved = problem.setup->getProblemDefinition()->hasExactSolution();
        s.pc_rrt_tree = dynamic_cast<const pd::SeededRRT *>(&pd::innerPlanner(planner)) != nullptr;
        s.restarts = pd::restartsOf(planner);
        s.steps = model->propagationSteps();
        s.own_steps = model->propagator().steps();
        ob::PlannerData data(problem.setup->getSpaceInformation());
        planner->getPlannerData(data);
        s.tree_states = data.numVertices();
        // The goal object's (x, y, yaw) follow the joints in a flat state.
        const std::size_t at = model->info().dof + 3 * static_cast<std::size_t>(model->info().goal_object);
        std::vector<double> start, vertex;
        model->view()->read(problem.setup->getProblemDefinition()->getStartState(0), start);
        for (unsigned v = 0; v < data.numVertices(); ++v)
        {
            model->view()->read(data.getVertex(v).getState(), vertex);
            if (!std::equal(vertex.begin() + at, vertex.begin() + at + 3, start.begin() + at))
                ++s.goal_object_moved;
        }
        if (const pd::Fallback *fallback = pd::wrapperOf<pd::Fallback>(planner); fallback && fallback->fellBack())
        {
            for (std::size_t i = 0; i < fallback->fallbacks().size(); ++i)
            {
                const pd::Search &pc_rrt = fallback->fallbacks()[i];
                ob::PlannerData trees(pc_rrt.problem.setup->getSpaceInformation());
                pc_rrt.planner->getPlannerData(trees);
                for (unsigned v = 0; v < trees.numVertices(); ++v)
                {
                    model->view()->read(trees.getVertex(v).getState(), vertex);
                    s.pc_rrt_vertices.push_back(vertex);
                }
            }
        }
        if (problem.setup->getProblemDefinition()->hasSolution())
            s.path = model->view()->readPath(problem.setup->getSolutionPath());
        return s;
    }

    /// Whether `path` is what its controls do: each state propagated from the one before
    /// with a model of its own (the scene loaded again), bit for bit, from the scene's
    /// start; and whether its last state is in the goal region (goal distance <= 0).
    bool reproducedToGoal(const std::string &scene, const pd::FlatPath &path)
    {
        const rust::Box<pushplan::bridge::Problem> problem = pushplan::bridge::Problem::load(scene);
        rust::Box<pushplan::bridge::Propagator> propagator = pushplan::bridge::Propagator::make(*problem);
        const rust::Box<pushplan::bridge::Goal> goal = pushplan::bridge::Goal::make(*problem);
        const pushplan::bridge::SceneInfo info = problem->info();
        const std::size_t n = info.start.size(), m = 3 + info.dof;
        if (path.steps.empty() || path.states.size() != n * (path.steps.size() + 1) ||
            !std::equal(info.start.begin(), info.start.end(), path.states.begin()))
            return false;
        std::vector<double> next(n);
        const rust::Slice<const double> none;
        for (std::size_t k = 0; k < path.steps.size(); ++k)
        {
            const rust::Slice<const double> x(path.states.data() + k * n, n), u(path.controls.data() + k * m, m);
            if (!propagator->propagate(x, none, u, path.steps[k], rust::Slice<double>(next.data(), n),
                                       rust::Slice<double>()) ||
                !std::equal(next.begin(), next.end(), path.states.begin() + (k + 1) * n))
                return false;
        }
        return goal->distance(rust::Slice<const double>(next.data(), n), none) <= 0.0;
    }

    /// How many of `path`'s states, from its first, are vertices of the fallback's PC RRT trees.
    std::size_t statesInTree(const Search &search, const pd::FlatPath &path)
    {
        const std::size_t n = search.pc_rrt_vertices.empty() ? 1 : search.pc_rrt_vertices.front().size();
        std::size_t k = 0;
        for (; (k + 1) * n <= path.states.size(); ++k)
        {
            const auto at = path.states.begin() + static_cast<std::ptrdiff_t>(k * n);
            const bool in_tree = std::any_of(search.pc_rrt_vertices.begin(), search.pc_rrt_vertices.end(),
                                             [&](const std::vector<double> &v) { return std::equal(v.begin(), v.end(), at); });
            if (!in_tree)
                break;
        }
        return k;
    }

    bool same(const Search &a, const Search &b)
    {
        return a.steps == b.steps && a.tree_states == b.tree_states && test::samePath(a.path, b.path);
    }
}  // namespace

int main()
{
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    constexpr std::uint64_t patience = 20000, budget = 60000;

    // Dense 17: the arm must swing round the clutter before the goal box can move.
    const std::string dense = "scenes/dense/scene_17.yaml";
    const Search alone = search(dense, 0, 0, patience);
    std::cout << "  dense 17, Push KPIECE alone: " << alone.tree_states << " states, "
              << alone.goal_object_moved << " with the goal object moved\n";
    expect(alone.tree_states > 100 && alone.goal_object_moved == 0,
           "dense 17: within the patience, no state of Push KPIECE's tree has moved the goal object");
    const Search handed = search(dense, patience, 0, budget);
    expect(handed.fell_back && handed.pc_rrt_tree && handed.tree_states > 1,
           "so it hands over, and the tree searched on is PC RRT's");
    expect(same(handed, search(dense, patience, 0, budget)), "the same handover and search again, bit for bit");
    const Search two_lanes = search(dense, patience, 0, budget, 2, 1);
    expect(two_lanes.fell_back && same(two_lanes, search(dense, patience, 0, budget, 2, 2)),
           "with two lanes, the same on one thread and on two");
    // Three lanes: a search on two threads, whose fallback is two PC RRTs, the second on
    // lane 1's model; its steps are credited to the search's model after each round.
    const Search three_lanes = search(dense, patience, 0, budget, 3, 2);
    std::cout << "  three lanes: " << three_lanes.own_steps << " of " << three_lanes.steps
              << " steps on the search's own model\n";
    // Before the handover the lanes propagate; after it the first PC RRT on the search's
    // own model takes about half the steps left, not all of them.
    expect(three_lanes.fell_back && three_lanes.steps >= budget && three_lanes.own_steps > 0 &&
               4 * three_lanes.own_steps < 3 * (three_lanes.steps - patience),
           "with three lanes, the fallback's two searches share the budget after the handover");
    expect(same(three_lanes, search(dense, patience, 0, budget, 3, 1)) &&
               same(three_lanes, search(dense, patience, 0, budget, 3, 2)),
           "and they are the same on one thread and on two, and again");
    // Robust planning sets a solution aside and starts the search over (clear()): after
    // the handover the fallback starts over, not Push KPIECE, which could not move the
    // goal object and, the model having met the fallback's moves, would not hand over again.
    {
        const test::SearchRun run =
            test::runSearch(dense, PlannerKind::PushKpiece, kSeed, 0, 0, 0, patience, budget);
        run.planner->clear();
        const std::uint64_t more = run.model->propagationSteps() + 5000;
        run.planner->solve(ob::PlannerTerminationCondition([&] { return run.model->propagationSteps() >= more; }));
        ob::PlannerData data(run.problem.setup->getSpaceInformation());
        run.planner->getPlannerData(data);
        std::cout << "  cleared after the handover, 5 000 steps: " << data.numVertices() << " states\n";
        expect(pd::fellBack(run.planner) && dynamic_cast<const pd::SeededRRT *>(&pd::innerPlanner(run.planner)) &&
                   data.numVertices() > 1 && data.numVertices() < handed.tree_states,
               "cleared after the handover, it searches on in a new PC RRT tree");
    }
    // Attempts of 3 000 x Luby(i) steps end at 3 000, 6 000, 12 000, 15 000 and 18 000.
    const Search restarting = search(dense, patience, 3000, budget);
    std::cout << "  with restarts: " << restarting.restarts << " before the handover\n";
    expect(restarting.fell_back && restarting.restarts == 5,
           "the restarts before the handover are still counted after it");

    // Benchmark scene 01 with a patience of 200 steps: Push KPIECE hands over before its
    // hand has reached the goal box; PC RRT's tree soon pushes the box nearer the goal,
    // and Push KPIECE searches on from there. The plan begins in PC RRT's tree and leaves
    // it where Push KPIECE took over.
    {
        const std::string scene = "scenes/benchmark/scene_01.yaml";
        const Search back = search(scene, 200, 0, 200000);
        const std::size_t in_tree = statesInTree(back, back.path);
        std::cout << "  scene 01, a patience of 200 steps: handed back " << back.handed_back << " time(s), "
                  << back.path.steps.size() << " controls, the first " << in_tree << " states in PC RRT's tree\n";
        expect(back.fell_back && back.handed_back == 1 && back.solved, "scene 01: it hands over, then back, and solves");
        expect(reproducedToGoal(scene, back.path),
               "the joined plan is what its controls do from the start, and it ends in the goal region");
        expect(in_tree >= 2 && in_tree <= back.path.steps.size(),
               "it begins with PC RRT's path (more than the start) and ends beyond PC RRT's tree");
        const Search back_again = search(scene, 200, 0, 200000);
        expect(same(back, back_again) && back_again.handed_back == 1, "the same plan again, bit for bit");
        const Search lanes_one = search(scene, 200, 0, 200000, 3, 1);
        const Search lanes_two = search(scene, 200, 0, 200000, 3, 2);
        std::cout << "  three lanes: handed back " << lanes_two.handed_back << " time(s), "
                  << (lanes_two.solved ? "solved" : "not solved") << "\n";
        expect(lanes_two.fell_back && lanes_two.handed_back >= 1 && lanes_two.solved &&
                   reproducedToGoal(scene, lanes_two.path) && same(lanes_one, lanes_two),
               "with three lanes (two PC RRTs), the same on one thread and on two, and a plan that is what it does");
    }

    // Benchmark scene 22: Push KPIECE moves the goal box early but does not solve the
    // scene within the budget; the fallback never fires and the search is the one without
    // it.
    const std::string pushed = "scenes/benchmark/scene_22.yaml";
    const Search progress = search(pushed, 0, 0, patience);
    std::cout << "  scene 22, Push KPIECE alone: " << progress.goal_object_moved << " of " << progress.tree_states
              << " states with the goal object moved\n";
    expect(progress.goal_object_moved > 0, "scene 22: within the patience, states that have moved the goal object");
    const Search kept = search(pushed, patience, 0, budget);
    const Search without = search(pushed, 0, 0, budget);
    expect(!kept.fell_back && !kept.pc_rrt_tree && same(kept, without),
           "so it keeps its search: the same tree and path as without a fallback");
    return test::failures == 0 ? 0 : 1;
}
