// Bring your own OMPL planner: pushplan's problem (pushplan/ompl.h) solved by OMPL's SST.
//   build/ompl_sst [scene] [seconds]
#include <pushplan/ompl.h>

#include <ompl/control/planners/sst/SST.h>

#include <ompl/util/Console.h>

#include <iostream>
#include <string>

int main(int argc, char **argv)
{
    const std::string scene = argc > 1 ? argv[1] : "scenes/herb_single_object.yaml";
    const double seconds = argc > 2 ? std::stod(argv[2]) : 5.0;
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);  // OMPL's progress messages off
    try
    {
        pushplan::SetupOptions options;
        options.seed = 1;
        const ompl::control::SimpleSetupPtr setup = pushplan::makeSetup(pushplan::Planner(scene), options);
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
