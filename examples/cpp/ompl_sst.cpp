// Bring your own OMPL planner: pushplan's problem (pushplan/ompl.h) solved by OMPL's SST.
//   build/ompl_sst [scene] [seconds]
// SST stops at its first solution (or after `seconds`), so the same scene gives the same
// plan on a fast machine and on a slow one.
#include <pushplan/ompl.h>

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/control/planners/sst/SST.h>
#include <ompl/util/RandomNumbers.h>

#include <ompl/util/Console.h>

#include <iostream>
#include <limits>
#include <string>

int main(int argc, char **argv)
{
    const std::string scene = argc > 1 ? argv[1] : "scenes/herb_single_object.yaml";
    const double seconds = argc > 2 ? std::stod(argv[2]) : 5.0;
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);  // OMPL's progress messages off
    // pushplan seeds its own samplers (SetupOptions::seed); SST's own random choices draw
    // from OMPL's global seed, which must be set before any OMPL object exists.
    ompl::RNG::setSeed(1);
    try
    {
        pushplan::SetupOptions options;
        options.seed = 1;
        const ompl::control::SimpleSetupPtr setup = pushplan::makeSetup(pushplan::Planner(scene), options);
        // SST is asymptotically optimal: it runs until its objective is satisfied or the
        // time is up. A threshold of infinity is met by any solution: stop at the first.
        auto objective = std::make_shared<ompl::base::PathLengthOptimizationObjective>(setup->getSpaceInformation());
        objective->setCostThreshold(ompl::base::Cost(std::numeric_limits<double>::infinity()));
        setup->setOptimizationObjective(objective);
        setup->setPlanner(std::make_shared<ompl::control::SST>(setup->getSpaceInformation()));
        setup->solve(seconds);
        if (!setup->haveExactSolutionPath())
        {
            std::cout << "not solved\n";
            return 1;
        }
        ompl::control::PathControl &path = setup->getSolutionPath();
        const pushplan::StateAccess states(setup->getStateSpace());
        const Eigen::Vector3d end = states.objectPose(path.getStates().back(), 0);
        std::cout << "SST solved: " << path.getControlCount() << " controls, " << path.getStates().size()
                  << " states, path " << (path.check() ? "valid" : "INVALID") << "; " << states.objectNames()[0]
                  << " ends at (" << end.x() << ", " << end.y() << ")\n";
        return 0;
    }
    catch (const pushplan::Error &e)
    {
        std::cerr << "pushplan error: " << e.what() << "\n";
        return 2;
    }
}
