// pushplan's problem as OMPL objects: for applications that bring their own OMPL
// planner, projection or benchmark.
//
//   pushplan::Planner scene("scenes/herb_fig1_clutter.yaml");
//   ompl::control::SimpleSetupPtr setup = pushplan::makeSetup(scene);
//   setup->setPlanner(std::make_shared<ompl::control::SST>(setup->getSpaceInformation()));
//   setup->solve(10.0);
//   pushplan::StateAccess states(setup->getStateSpace());
//   Eigen::Vector3d box = states.objectPose(setup->getSolutionPath().getStates().back(), 0);
//
// The setup carries pushplan's state space (joints x one SE(2) per object, the model's
// weighted distance), control space (end-effector velocity and null-space sample) with
// its control sampler, the directed control sampler that keeps the best of k, the state
// propagator (the quasistatic pushing physics), the validity checker, the start, the goal
// (a GoalSampleableRegion: the goal object in its disc), a path-length objective and the
// default projection (end-effector xy, goal-object xy and the blockage of the goal object's
// way, for KPIECE1, EST, PDST). No
// planner is set. Objects keep their model alive: the setup may outlive the Planner.
#pragma once

#include <pushplan/pushplan.h>

#include <ompl/base/StateSpace.h>
#include <ompl/control/SimpleSetup.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace pushplan
{
    /// The OMPL problem of `planner`'s scene (see the top of this header). Throws
    /// pushplan::Error for bad options.
    std::shared_ptr<ompl::control::SimpleSetup> makeSetup(const Planner &planner,
                                                          const SetupOptions &options = SetupOptions());

    /// Reads and writes pushplan's states: the joints (rad or m, in the URDF's order) and
    /// each object's planar pose (x, y in m, yaw in rad, world frame). Works on any state
    /// of the space it was made from.
    class StateAccess
    {
    public:
        /// Throws pushplan::Error if `space` is not pushplan's state space.
        explicit StateAccess(ompl::base::StateSpacePtr space);

        std::size_t dof() const { return dof_; }
        std::size_t objectCount() const { return objects_; }
        const std::vector<std::string> &jointNames() const { return joint_names_; }
        const std::vector<std::string> &objectNames() const { return object_names_; }

        Eigen::VectorXd joints(const ompl::base::State *state) const;
        Eigen::Vector3d objectPose(const ompl::base::State *state, std::size_t object) const;
        void setJoints(ompl::base::State *state, const Eigen::VectorXd &q) const;
        void setObjectPose(ompl::base::State *state, std::size_t object, const Eigen::Vector3d &pose) const;

    private:
        ompl::base::StateSpacePtr space_;
        std::size_t dof_, objects_;
        std::vector<std::string> joint_names_, object_names_;
    };
}  // namespace pushplan
