// KPIECE1 on pushplan's problem with a projection of your own: here the goal object's
// position alone, in 2 cm cells.
//   build/ompl_kpiece_projection [scene] [seconds]
#include <pushplan/ompl.h>

#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>

#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <iostream>
#include <string>

/// The goal object's (x, y), read with pushplan::StateAccess.
class GoalObjectProjection : public ompl::base::ProjectionEvaluator
{
public:
    GoalObjectProjection(const ompl::base::StateSpacePtr &space, std::size_t object)
      : ompl::base::ProjectionEvaluator(space), states_(space), object_(object)
    {
    }
    unsigned int getDimension() const override { return 2; }
    void defaultCellSizes() override { cellSizes_.assign(2, 0.02); }
    void project(const ompl::base::State *state, Eigen::Ref<Eigen::VectorXd> projection) const override
    {
        projection = states_.objectPose(state, object_).head<2>();
    }

private:
    pushplan::StateAccess states_;
    std::size_t object_;
};

int main(int argc, char **argv)
{
    const std::string scene = argc > 1 ? argv[1] : "scenes/herb_single_object.yaml";
    const double seconds = argc > 2 ? std::stod(argv[2]) : 10.0;
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);  // OMPL's progress messages off
    // KPIECE1 draws its own seed from OMPL's process-wide generator: seeded, runs repeat.
    ompl::RNG::setSeed(1);
    try
    {
        const ompl::control::SimpleSetupPtr setup = pushplan::makeSetup(pushplan::Planner(scene));
        const ompl::base::StateSpacePtr &space = setup->getStateSpace();
        space->registerProjection("goal_object", std::make_shared<GoalObjectProjection>(space, 0));
        auto kpiece = std::make_shared<ompl::control::KPIECE1>(setup->getSpaceInformation());
        kpiece->setProjectionEvaluator("goal_object");
        setup->setPlanner(kpiece);
        const bool solved = setup->solve(seconds) == ompl::base::PlannerStatus::EXACT_SOLUTION;
        std::cout << "KPIECE1 with the goal object's projection: " << (solved ? "solved" : "not solved") << ", "
                  << (solved ? setup->getSolutionPath().getControlCount() : 0) << " controls\n";
        return solved ? 0 : 1;
    }
    catch (const pushplan::Error &e)
    {
        std::cerr << "pushplan error: " << e.what() << "\n";
        return 2;
    }
}
