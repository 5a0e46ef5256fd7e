// A C++ application using pushplan: plan a scene and print the plan; then, if asked,
// reach a grasp of an object where the plan leaves it (push, then grasp).
//
// Build (after `cargo build --release`), from the repository root:
//   g++ -o plan_scene examples/cpp/plan_scene.cpp $(pkg-config --cflags --libs target/release/pushplan.pc)
// Run:
//   ./plan_scene scenes/herb_single_object.yaml [seed [object-to-grasp]]
//   ./plan_scene - < scene.yaml       (a scene given as text, e.g. built by the program)
#include <pushplan/pushplan.h>

#include <cstdlib>
#include <iostream>
#include <iterator>
#include <string>

int main(int argc, char **argv)
{
    const std::string scene = argc > 1 ? argv[1] : "scenes/herb_single_object.yaml";
    try
    {
        pushplan::Planner planner =
            scene == "-" ? pushplan::Planner::fromYaml(std::string(std::istreambuf_iterator<char>(std::cin), {}),
                                                       "stdin.yaml") :
                           pushplan::Planner(scene);
        pushplan::Options options;
        options.time_limit = 30.0;
        options.seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
        const pushplan::Plan plan = planner.solve(options);

        std::cout << planner.sceneName() << ": " << (plan.solved ? "solved" : "not solved") << " in "
                  << plan.planning_time << " s, " << plan.controls.size() << " controls, " << plan.duration()
                  << " s of motion\n";
        const auto &last = plan.object_poses.back();
        for (std::size_t i = 0; i < plan.object_names.size(); ++i)
            std::cout << "  " << plan.object_names[i] << " ends at (" << last[i].x() << ", " << last[i].y()
                      << ", " << last[i].z() << ")\n";
        std::cout << "  manipulator path " << plan.after_shortcut.joint_length << " rad (found: "
                  << plan.before_shortcut.joint_length << " rad), " << plan.after_shortcut.links_in_contact
                  << " links made contact\n";
        std::size_t pushes = 0;
        for (const auto &contacts : plan.contacts)
            pushes += contacts.size();
        std::cout << "  " << pushes << " link-object pushes over " << plan.joint_trajectory.size() << " states of "
                  << plan.joint_trajectory.front().size() << " joints\n";
        const auto &trajectory = plan.trajectory;
        std::cout << "  trajectory: " << trajectory.times.size() << " samples at " << trajectory.rate << " Hz, "
                  << trajectory.times.back() << " s; first joint ends at " << trajectory.q.back()[0] << "\n";
        if (argc > 3 && plan.solved)
        {
            // IK-BiRRT from where the plan ends, every object a static obstacle.
            pushplan::ReachOptions reach_options;
            reach_options.seed = options.seed;
            const pushplan::Reach reach = planner.reach(argv[3], reach_options, &plan);
            std::cout << "  then a grasp of " << reach.object << ": " << (reach.solved ? "reached" : "not reached")
                      << " through " << reach.waypoints.size() << " waypoints (" << reach.goal_samples
                      << " IK solutions in the goal tree)\n";
            return reach.solved ? 0 : 1;
        }
        return plan.solved ? 0 : 1;
    }
    catch (const pushplan::Error &e)
    {
        std::cerr << "pushplan error: " << e.what() << "\n";
        return 2;
    }
}
