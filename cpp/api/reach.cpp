// pushplan::Planner::reach: IK-BiRRT to a grasp of an object, every object a static
// obstacle, the reach checked by the model before it is returned.

#include "pushplan/pushplan.h"

#include "pushplan/cpp/problem/arm_space.h"
#include "pushplan/cpp/planners/ik_birrt/ik_birrt.h"
#include "pushplan/cpp/problem/model_handle.h"
#include "pushplan/cpp/api/planner_source.h"
#include "pushplan/cpp/problem/problem.h"

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Console.h>

#include <chrono>
#include <cmath>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace pushplan
{
    namespace detail
    {
        /// The full state a reach starts from: the scene's start, or the end of `after`.
        FlatState reachStart(const bridge::SceneInfo &info, const Plan *after)
        {
            FlatState from(info.start.begin(), info.start.end());
            if (after == nullptr)
                return from;
            if (after->joint_trajectory.empty() || after->object_poses.size() != after->joint_trajectory.size())
                throw Error("reach: the plan to reach from has no states");
            const Eigen::VectorXd &q = after->joint_trajectory.back();
            const auto &poses = after->object_poses.back();
            if (static_cast<std::size_t>(q.size()) != info.dof || poses.size() != info.objects)
                throw Error("reach: the plan to reach from is not of this scene");
            for (std::size_t i = 0; i < info.dof; ++i)
                from[i] = q[static_cast<Eigen::Index>(i)];
            for (std::size_t o = 0; o < info.objects; ++o)
                for (std::size_t c = 0; c < 3; ++c)
                    from[FlatLayout{info.dof, info.objects}.object(o) + c] = poses[o][static_cast<Eigen::Index>(c)];
            return from;
        }
    }  // namespace detail

    Reach Planner::reach(const std::string &object, const ReachOptions &options, const Plan *after) const
    {
        const Source &source = this->source();
        return detail::reach([&] { return source.load(); }, object,
                             [&](const bridge::SceneInfo &info) {
                                 return detail::ReachSettings{options.time_limit.value_or(info.planner.time_limit),
                                                              options.seed.value_or(info.planner.seed),
                                                              options.sample_probability};
                             },
                             [&](const bridge::SceneInfo &info) { return detail::reachStart(info, after); });
    }

    Reach detail::reach(const std::function<rust::Box<bridge::Problem>()> &load, const std::string &object,
                        const std::function<ReachSettings(const bridge::SceneInfo &)> &settings_of,
                        const std::function<std::vector<double>(const bridge::SceneInfo &)> &start_of)
    {
        return detail::asPushplanError([&] {
            const detail::ModelHandle model(load());
            const bridge::SceneInfo &info = model.info();
            const rust::Box<bridge::Grasping> grasping = bridge::Grasping::make(model.problem());
            const std::size_t index = grasping->graspable_object(object);
            const ReachSettings settings = settings_of(info);
            const double time_limit = settings.time_limit;
            detail::checked("time_limit", time_limit, std::isfinite(time_limit) && time_limit > 0.0);
            detail::checked("sample_probability", settings.sample_probability,
                            settings.sample_probability >= 0.0 && settings.sample_probability <= 1.0);
            const std::uint64_t seed = settings.seed;
            const detail::FlatState from = start_of(info);

            ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
            detail::ArmSpace space(model);
            space.context() = from;
            space.seedSamplers(detail::subSeed(seed, 1));
            const ob::SpaceInformationPtr &si = space.si();
            auto pdef = std::make_shared<ob::ProblemDefinition>(si);
            ob::ScopedState<> start(si);
            space.toArm(from, start.get());
            pdef->addStartState(start);
            pdef->setGoal(std::make_shared<detail::GraspGoal>(space, model, from, index, detail::subSeed(seed, 2)));
            detail::IkBiRrt planner(si, detail::subSeed(seed, 0));
            planner.setSampleProbability(settings.sample_probability);
            planner.setProblemDefinition(pdef);
            planner.setup();

            const auto began = std::chrono::steady_clock::now();
            const ob::PlannerStatus status = planner.solve(ob::timedPlannerTerminationCondition(time_limit));
            Reach reach;
            reach.object = object;
            reach.planning_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
            reach.goal_samples = planner.goalSamples();
            reach.tree_size = planner.treeSize();
            if (status != ob::PlannerStatus::EXACT_SOLUTION)
                return reach;
            const auto &path = *pdef->getSolutionPath()->as<og::PathGeometric>();
            std::vector<double> flat;
            detail::FlatState full = from;
            for (std::size_t k = 0; k < path.getStateCount(); ++k)
            {
                space.withJoints(path.getState(k), full);
                reach.waypoints.emplace_back(Eigen::Map<const Eigen::VectorXd>(full.data(), info.dof));
                flat.insert(flat.end(), full.begin(), full.begin() + info.dof);
            }
            // Every reach returned is checked by the model, independently of the search.
            const rust::String problem = grasping->check_reach(detail::slice(from), index, detail::slice(flat));
            if (!problem.empty())
                throw Error("internal error: IK-BiRRT's reach does not check: " + std::string(problem));
            reach.solved = true;
            return reach;
        });
    }
}  // namespace pushplan
