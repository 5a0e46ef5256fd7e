// The public OMPL layer (pushplan/ompl.h): the problem Planner::solve searches, handed
// to the application.

#include "pushplan/ompl.h"

#include "pushplan/cpp/problem/model_handle.h"
#include "pushplan/cpp/api/planner_source.h"
#include "pushplan/cpp/api/search_builder.h"
#include "pushplan/cpp/problem/problem.h"
#include "pushplan/cpp/problem/state_space.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace pushplan
{
    std::shared_ptr<oc::SimpleSetup> makeSetup(const Planner &planner, const SetupOptions &options)
    {
        return detail::asPushplanError([&] {
            const Planner::Source &source = planner.source();
            detail::SearchBuilder builder([&] { return source.load(); });
            const bridge::SceneInfo &info = builder.info();
            const unsigned k = options.k.value_or(info.planner.k);
            if (k < 1)
                throw Error("SetupOptions::k must be at least 1");
            return detail::makeProblem(builder.model(options.static_clutter), options.seed.value_or(info.planner.seed), k)
                .setup;
        });
    }

    StateAccess::StateAccess(ob::StateSpacePtr space) : space_(std::move(space))
    {
        const auto *pushplan_space = dynamic_cast<const detail::PushStateSpace *>(space_.get());
        if (pushplan_space == nullptr)
            throw Error("StateAccess: '" + (space_ ? space_->getName() : std::string("null")) +
                        "' is not pushplan's state space (make it with pushplan::makeSetup)");
        const bridge::SceneInfo &info = pushplan_space->view()->info();
        dof_ = info.dof;
        objects_ = info.objects;
        for (const auto &n : info.joint_names)
            joint_names_.emplace_back(n);
        for (const auto &n : info.object_names)
            object_names_.emplace_back(n);
    }

    namespace
    {
        void checkObject(std::size_t object, std::size_t objects)
        {
            if (object >= objects)
                throw Error("StateAccess: object " + std::to_string(object) + " of " + std::to_string(objects));
        }
    }  // namespace

    // The state is the compound [joints (RealVector), object 1 (SE2), ...].
    Eigen::VectorXd StateAccess::joints(const ob::State *state) const
    {
        const double *q = state->as<ob::CompoundState>()->as<ob::RealVectorStateSpace::StateType>(0)->values;
        return Eigen::Map<const Eigen::VectorXd>(q, static_cast<Eigen::Index>(dof_));
    }

    Eigen::Vector3d StateAccess::objectPose(const ob::State *state, std::size_t object) const
    {
        checkObject(object, objects_);
        const auto *pose = state->as<ob::CompoundState>()->as<ob::SE2StateSpace::StateType>(1 + object);
        return {pose->getX(), pose->getY(), pose->getYaw()};
    }

    void StateAccess::setJoints(ob::State *state, const Eigen::VectorXd &q) const
    {
        if (static_cast<std::size_t>(q.size()) != dof_)
            throw Error("StateAccess::setJoints: " + std::to_string(q.size()) + " values for " +
                        std::to_string(dof_) + " joints");
        double *values = state->as<ob::CompoundState>()->as<ob::RealVectorStateSpace::StateType>(0)->values;
        Eigen::Map<Eigen::VectorXd>(values, static_cast<Eigen::Index>(dof_)) = q;
    }

    void StateAccess::setObjectPose(ob::State *state, std::size_t object, const Eigen::Vector3d &pose) const
    {
        checkObject(object, objects_);
        auto *se2 = state->as<ob::CompoundState>()->as<ob::SE2StateSpace::StateType>(1 + object);
        se2->setXY(pose.x(), pose.y());
        se2->setYaw(pose.z());
    }
}  // namespace pushplan
