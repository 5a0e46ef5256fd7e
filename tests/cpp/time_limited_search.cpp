// TimeLimitedSearch (run by tests/integration/cpp_api.rs, built with the library's internal headers):
// the model's time limit holds while the search runs and is lifted when it returns, so
// what OMPL's tooling propagates again afterwards is right. The oracle is the planner
// data's own edges: each one's control, held for its duration from its source, must
// reach its target. PDST builds its edges by propagating every motion again (a motion
// split across cells is found step by step), which the limit used to refuse.
#include "pushplan/cpp/problem/problem.h"
#include "pushplan/cpp/search/restarts.h"
#include "pushplan/cpp/search/wrapped_search.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/control/PlannerData.h>
#include <ompl/util/Console.h>

#include "expect.h"

#include <iostream>
#include <string>
#include <vector>

namespace
{
    namespace ob = ompl::base;
    namespace oc = ompl::control;
    namespace pd = pushplan::detail;
    using test::expect;

    struct Edges
    {
        unsigned checked = 0;
        unsigned reproduced = 0;
    };

    /// Every control edge of `data`, propagated again from its source.
    Edges reproduce(const oc::PlannerData &data, const oc::SpaceInformationPtr &si)
    {
        Edges edges;
        ob::State *end = si->allocState();
        for (unsigned v = 0; v < data.numVertices(); ++v)
        {
            std::vector<unsigned> targets;
            data.getEdges(v, targets);
            for (unsigned w : targets)
            {
                const auto &edge = static_cast<const oc::PlannerDataEdgeControl &>(data.getEdge(v, w));
                const auto steps = static_cast<unsigned>(edge.getDuration() / si->getPropagationStepSize() + 0.5);
                si->propagate(data.getVertex(v).getState(), edge.getControl(), steps, end);
                ++edges.checked;
                if (si->distance(end, data.getVertex(w).getState()) < 1e-9)
                    ++edges.reproduced;
            }
        }
        si->freeState(end);
        return edges;
    }
}  // namespace

int main()
{
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    // A dense scene PDST does not solve in a fraction of a second: the search runs until
    // its limit, and its tree is read after it.
    const std::string scene = "scenes/dense/scene_17.yaml";
    const pd::ModelHandlePtr model = std::make_shared<pd::ModelHandle>(pushplan::bridge::Problem::load(scene));
    const unsigned k = model->info().planner.k;
    const pd::Problem problem = pd::makeProblem(model, 3, k);
    const double limit = 0.5;
    const auto planner = std::make_shared<pd::TimeLimitedSearch>(
        pd::makePlanner(pushplan::PlannerKind::Pdst, problem, 3, 0.05, false, 0, 0), std::vector{model}, limit);
    problem.setup->setPlanner(planner);
    problem.setup->setup();
    expect(planner->getName() == "PDST" && &pd::innerPlanner(planner) == planner->search().get() &&
               pd::restartsOf(planner) == 0,
           "the wrapper carries its search's name and is seen through");

    const ob::PlannerStatus status = planner->solve(ob::timedPlannerTerminationCondition(limit));
    expect(status != ob::PlannerStatus::EXACT_SOLUTION, "PDST ran until the limit without solving");

    oc::PlannerData data(problem.setup->getSpaceInformation());
    planner->getPlannerData(data);
    const Edges edges = reproduce(data, problem.setup->getSpaceInformation());
    std::cout << "  " << data.numVertices() << " states, " << edges.reproduced << " of " << edges.checked
              << " edges reproduced\n";
    expect(edges.checked > 100 && edges.reproduced == edges.checked,
           "after the search, every edge of its tree is reproduced by propagating it again");
    return test::failures == 0 ? 0 : 1;
}
