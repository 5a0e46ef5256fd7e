// An ompl::tools::Benchmark of your own on pushplan's problem: OMPL's SST and KPIECE1
// side by side; the log goes to the file given (ompl_benchmark_statistics reads it).
//   build/ompl_benchmark [scene] [log] [seconds per run] [runs]
#include <pushplan/ompl.h>

#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/sst/SST.h>
#include <ompl/tools/benchmark/Benchmark.h>

#include <ompl/util/Console.h>

#include <iostream>
#include <string>

int main(int argc, char **argv)
{
    const std::string scene = argc > 1 ? argv[1] : "scenes/herb_single_object.yaml";
    const std::string log = argc > 2 ? argv[2] : "benchmark.log";
    const double seconds = argc > 3 ? std::stod(argv[3]) : 5.0;
    const unsigned runs = argc > 4 ? static_cast<unsigned>(std::stoul(argv[4])) : 3;
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);  // OMPL's progress messages off
    try
    {
        const ompl::control::SimpleSetupPtr setup = pushplan::makeSetup(pushplan::Planner(scene));
        ompl::tools::Benchmark benchmark(*setup, "pushplan: " + scene);
        benchmark.addPlanner(std::make_shared<ompl::control::SST>(setup->getSpaceInformation()));
        benchmark.addPlanner(std::make_shared<ompl::control::KPIECE1>(setup->getSpaceInformation()));
        // No console capture file in the working directory (OMPL writes one by default).
        benchmark.benchmark(ompl::tools::Benchmark::Request(seconds, 4096.0, runs, 0.5, false, false));
        if (!benchmark.saveResultsToFile(log.c_str()))
            return 2;
        std::cout << "benchmark log written to " << log << "\n";
        return 0;
    }
    catch (const pushplan::Error &e)
    {
        std::cerr << "pushplan error: " << e.what() << "\n";
        return 2;
    }
}
