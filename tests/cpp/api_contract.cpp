// The C++ API's contract beyond planning (run by tests/integration/cpp_api.rs):
// - every planner kind has the CLI's name, and a name gives the kind back;
// - progress reaches Options::on_progress; a semi-dynamic scene plans; a robust plan is
//   as robust as the default rate asks;
// - Planner::reach reaches a grasp behind a wall with IK-BiRRT, and after a pushing plan;
//   a grasp goal's samples (inverse kinematics of its regions) satisfy it;
// - closing the loop: Planner::replan keeps the rest of a plan when the world is where the
//   plan said, repairs it where a box was moved (the rest kept, an ending searched from
//   where it ends), searches anew with no rest to keep (each new plan starting at the
//   observed state), and refuses an observation of the wrong size or an invalid one;
// - OMPL's process-wide log level is as the application left it after solve();
// - every failure crosses as pushplan::Error: an unknown name, each bad option, a planner
//   whose paths are not controls, a bad scene, an observed start the model refuses inside
//   solveFrom(), an integer cast to PlannerKind, a moved-from planner;
// - closed-loop execution (pushplan::Executor): a plan played as it is where the world is
//   where the plan said, re-planned where the box is found elsewhere and played to its
//   end; an option out of its limit, an unsolved plan, an observation of the wrong size
//   refused as pushplan::Error, one that is no valid start a stop that says why;
// - a Planner reads its scene file once: with the file removed it still plans and re-plans;
// - the public OMPL layer (pushplan/ompl.h): the state space passes OMPL's own sanity
//   checks, StateAccess reads what it wrote, and no state outside OMPL's bounds is valid.
// Prints one line per check; exits non-zero at the first failure.
#include <pushplan/ompl.h>
#include <pushplan/pushplan.h>

#include <ompl/base/goals/GoalSampleableRegion.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <ompl/util/Console.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>
#include "expect.h"

#include <iostream>
#include <string>
#include <vector>

namespace
{
    using test::expect;
    using test::failures;

    /// The planar hand's box (scenes/planar_hand_single_object.yaml) found 5 cm further from
    /// the hand at `q` and 10 cm to the side, away from the goal disc's centre (0.85, 0.1).
    void move_the_box(Eigen::Vector3d &box, const Eigen::VectorXd &q)
    {
        const Eigen::Vector2d away = (box.head<2>() - q.head<2>()).normalized();
        const Eigen::Vector2d side(-away.y(), away.x());
        box.head<2>() += 0.05 * away + ((0.85 - box.x()) * side.x() + (0.1 - box.y()) * side.y() > 0 ? -0.1 : 0.1) * side;
    }

    /// Runs `f`; true if it threw pushplan::Error whose message contains `text`.
    bool throwsError(const std::function<void()> &f, const std::string &text)
    {
        try
        {
            f();
        }
        catch (const pushplan::Error &e)
        {
            return std::string(e.what()).find(text) != std::string::npos;
        }
        catch (...)
        {
            return false;
        }
        return false;
    }
}  // namespace

int main()
{
    using pushplan::PlannerKind;
    const PlannerKind all[] = {PlannerKind::PcRrt, PlannerKind::StaticRrt, PlannerKind::Darrt,
                               PlannerKind::Kpiece, PlannerKind::Est,       PlannerKind::Pdst,
                               PlannerKind::Sst,    PlannerKind::DarrtPickPlace, PlannerKind::PushKpiece};
    const char *names[] = {"pcrrt", "static", "darrt", "kpiece", "est", "pdst", "sst", "darrt_pick", "push_kpiece"};
    for (int i = 0; i < 9; ++i)
    {
        expect(pushplan::plannerName(all[i]) == names[i], std::string("plannerName -> ") + names[i]);
        expect(pushplan::plannerKind(names[i]) == all[i], std::string("plannerKind(") + names[i] + ")");
    }
    // Bytes that are no UTF-8 (Rust takes UTF-8 only): pushplan::Error, not std::invalid_argument.
    expect(throwsError([] { pushplan::plannerKind("\xff\xfe"); }, "the planner kind's name is not UTF-8 text"),
           "plannerKind of bytes that are not UTF-8 throws pushplan::Error");
    expect(throwsError([] { pushplan::Planner::fromYaml("name: \xff", "bytes"); }, "the scene's YAML text is not UTF-8"),
           "Planner::fromYaml of bytes that are not UTF-8 throws pushplan::Error");
    expect(throwsError([] { pushplan::plannerKind("rrtstar"); }, "unknown planner 'rrtstar'"),
           "an unknown name throws pushplan::Error");

    const pushplan::Planner planner("scenes/herb_single_object.yaml");
    ompl::msg::setLogLevel(ompl::msg::LOG_DEBUG);
    pushplan::Options options;
    options.planner = PlannerKind::Kpiece;
    options.time_limit = 20.0;
    options.seed = 1;
    const pushplan::Plan plan = planner.solve(options);
    expect(plan.solved && !plan.controls.empty(), "KPIECE1 through the API solves the single-object scene");
    expect(ompl::msg::getLogLevel() == ompl::msg::LOG_DEBUG, "the log level is the application's after solve()");
    ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
    planner.solve(options);
    expect(ompl::msg::getLogLevel() == ompl::msg::LOG_ERROR, "... whatever it was");

    {
        // The semi-dynamic model (physics.model in the scene) through the same API, with
        // shortcutting.
        const pushplan::Planner workshop("scenes/workshop/scene_2.yaml");
        pushplan::Options o;
        o.seed = 1;
        o.threads = 1;
        o.time_limit = 60.0;
        o.shortcut = 0.5;
        const pushplan::Plan plan = workshop.solve(o);
        expect(plan.solved && !plan.controls.empty(),
               "the semi-dynamic model plans through the C++ API (the workshop's scene two)");
    }

    {
        // Robust planning through the API: the plan kept reaches the goal in at least the
        // default rate of its perturbed re-simulations, and says so.
        const pushplan::Planner hand("scenes/planar_hand_single_object.yaml");
        pushplan::Options o;
        o.seed = 1;
        o.threads = 1;
        o.time_limit = 30.0;
        o.robust_trials = 10;
        const pushplan::Plan plan = hand.solve(o);
        expect(plan.solved && !o.robust_rate && plan.robustness >= 0.95,
               "a robust plan through the API reaches the goal in 95 % of its perturbed re-simulations");
        expect(plan.robustness_trials == 10, "with time to spare, its robustness is over every trial asked");
        expect(plan.unseen_trials == 10 && plan.unseen_robustness >= 0.0 && plan.unseen_robustness <= 1.0,
               "and its rate in as many worlds it was not chosen in is given beside it");
        // With a thousand trials and a tenth of a second, the check stops at the limit:
        // over fewer trials, and says how many.
        o.robust_trials = 1000;
        o.time_limit = 0.1;
        const pushplan::Plan hurried = hand.solve(o);
        expect(hurried.robustness < 0 ? hurried.robustness_trials == 0
                                      : hurried.robustness_trials >= 1 && hurried.robustness_trials < 1000,
               "a robustness check the time limit cuts short is over the trials it ran");
        expect(hurried.unseen_robustness < 0 ? hurried.unseen_trials == 0
                                             : hurried.unseen_trials >= 1 && hurried.unseen_trials <= 1000,
               "so is the rate in other worlds, or it is not given");
    }

    {
        // Reaching a grasp with IK-BiRRT: from the start, over a wall; then after a
        // pushing plan (push, then grasp) from where the plan leaves the arm and objects.
        const pushplan::Planner walled("scenes/grasp_behind_wall.yaml");
        pushplan::ReachOptions r;
        r.seed = 1;
        r.time_limit = 60.0;
        const pushplan::Reach reach = walled.reach("can", r);
        expect(reach.solved && reach.waypoints.size() >= 2 && reach.goal_samples > 0 && reach.object == "can",
               "Planner::reach reaches a grasp of the can behind the wall");
        pushplan::Options o;
        o.seed = 1;
        o.threads = 1;
        o.time_limit = 60.0;
        o.shortcut = 0.0;
        const pushplan::Plan pushed = walled.solve(o);
        const pushplan::Reach then = walled.reach("box", r, &pushed);
        expect(pushed.solved && then.solved &&
                   (then.waypoints.front() - pushed.joint_trajectory.back()).norm() == 0.0,
               "Planner::reach after a pushing plan starts where the plan ends and reaches the box");
        bool refused = false;
        try
        {
            walled.reach("wall", r);
        }
        catch (const pushplan::Error &e)
        {
            refused = std::string(e.what()).find("objects with grasps: 'can', 'box'") != std::string::npos;
        }
        expect(refused, "Planner::reach of something without grasps throws pushplan::Error naming the graspable objects");
    }

    {
        // A progress callback that throws stops the search, and its own exception reaches
        // the caller (it once ended in std::terminate).
        const pushplan::Planner cluttered("tests/data/clutter_on_goal.yaml");
        pushplan::Options o;
        o.planner = PlannerKind::StaticRrt;
        o.time_limit = 30.0;
        o.seed = 1;
        o.threads = 2;
        o.on_progress = [](const pushplan::Progress &) { throw std::out_of_range("the application's own"); };
        const auto started = std::chrono::steady_clock::now();
        std::string caught;
        try
        {
            cluttered.solve(o);
        }
        catch (const std::out_of_range &e)
        {
            caught = e.what();
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        expect(caught == "the application's own" && seconds < 15.0,
               "an exception of on_progress stops the search and reaches the caller as thrown");
    }
    {
        // A search that cannot succeed (clutter pinned on the goal disc) reports once a
        // second to on_progress, with how close it has come.
        const pushplan::Planner cluttered("tests/data/clutter_on_goal.yaml");
        pushplan::Options o;
        o.planner = PlannerKind::StaticRrt;
        o.time_limit = 1.5;
        o.seed = 1;
        o.threads = 1;
        o.shortcut = 0.0;
        std::vector<pushplan::Progress> reports;
        o.on_progress = [&](const pushplan::Progress &p) { reports.push_back(p); };
        cluttered.solve(o);
        expect(!reports.empty() && reports[0].seconds >= 1.0 && reports[0].tree_states &&
                   *reports[0].tree_states > 0 && reports[0].propagation_steps > 0 &&
                   std::isfinite(reports[0].closest_goal_distance) && reports[0].closest_goal_distance > 0.0,
               "on_progress hears the search once a second: its tree, steps and closest goal distance");
    }

    options.time_limit = -1.0;
    expect(throwsError([&] { planner.solve(options); }, "time_limit"), "a bad option throws pushplan::Error");
    options.time_limit = 1.0;
    options.planner = PlannerKind::Darrt;
    expect(throwsError([&] { planner.solve(options); }, "DARRT"), "DARRT through solve() throws pushplan::Error");
    options.planner = PlannerKind::DarrtPickPlace;
    expect(throwsError([&] { planner.solve(options); }, "DARRT"),
           "DARRT with PickPlace through solve() throws pushplan::Error");
    expect(throwsError([] { pushplan::Planner("scenes/none.yaml"); }, "none.yaml"),
           "a missing scene throws pushplan::Error");
    // Every option is checked before the search, a bad one named.
    const auto bad_option = [&](const std::string &field, const std::function<void(pushplan::Options &)> &set) {
        pushplan::Options o;
        o.time_limit = 1.0;
        set(o);
        expect(throwsError([&] { planner.solve(o); }, field), "a bad " + field + " throws pushplan::Error");
    };
    bad_option("k", [](pushplan::Options &o) { o.k = 0u; });
    // The limits table's, as the CLI's: counts that once ran past a minute with
    // time_limit = 1 (k = 10^9, robust_trials = UINT_MAX), the limit named.
    bad_option("Options::k: must be in [1, 10000]", [](pushplan::Options &o) { o.k = 1000000000u; });
    bad_option("Options::robust_trials: must be in [0, 1000]",
               [](pushplan::Options &o) { o.robust_trials = std::numeric_limits<unsigned>::max(); });
    bad_option("Options::threads", [](pushplan::Options &o) { o.threads = 0u; });
    bad_option("Options::time_limit", [](pushplan::Options &o) { o.time_limit = 1e300; });
    bad_option("goal_bias", [](pushplan::Options &o) { o.goal_bias = 1.5; });
    bad_option("robust_rate", [](pushplan::Options &o) { o.robust_rate = 2.0; });
    bad_option("robust_shortcut", [](pushplan::Options &o) { o.robust_shortcut = -1.0; });
    bad_option("shortcut", [](pushplan::Options &o) { o.shortcut = std::nan(""); });
    // Perturbed worlds belong to robust planning of the pushing problem.
    bad_option("robust_particles", [](pushplan::Options &o) {
        o.robust_trials = 0u;  // the first solution as found: no robust planning
        o.robust_particles = 4;
    });
    bad_option("robust_particles", [](pushplan::Options &o) {
        o.robust_trials = 10;
        o.robust_particles = 4;
        o.planner = pushplan::PlannerKind::StaticRrt;
    });
    bad_option("robust_particles", [](pushplan::Options &o) {
        o.robust_trials = 10;
        o.robust_particles = 1000;
    });
    // Hostile use: an integer that is no PlannerKind, a planner moved from.
    const auto no_kind = static_cast<PlannerKind>(42);
    expect(throwsError([&] { pushplan::plannerName(no_kind); }, "unknown planner kind 42"),
           "plannerName of a value that is no PlannerKind throws pushplan::Error");
    bad_option("planner kind", [&](pushplan::Options &o) { o.planner = no_kind; });
    {
        pushplan::Planner moved("scenes/herb_single_object.yaml");
        const pushplan::Planner taker(std::move(moved));
        expect(taker.sceneName() == "herb-single-object", "a planner moved into works");
        expect(throwsError([&] { moved.solve(); }, "moved from"), "solve() on a moved-from planner throws");
        expect(throwsError([&] { moved.sceneName(); }, "moved from"), "sceneName() on a moved-from planner throws");
        expect(throwsError([&] { pushplan::makeSetup(moved); }, "moved from"),
               "makeSetup() of a moved-from planner throws");
    }
    // The scene check: nothing on a shipped scene; the pushing plane raised above the goal
    // box's tipping height (0.051 / 0.4 = 0.1275 m), one warning saying so.
    {
        const pushplan::Planner shipped("scenes/herb_single_object.yaml");
        expect(shipped.sceneWarnings().empty(), "a shipped scene has no scene warnings");
        std::ifstream in("scenes/herb_single_object.yaml");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        text.replace(text.find("pushing_plane: {height: 0.08"), 28, "pushing_plane: {height: 0.14");
        const auto warnings = pushplan::Planner::fromYaml(text, "scenes/high.yaml").sceneWarnings();
        expect(warnings.size() == 1 && warnings[0].find("'green_box' tips when the tool pushes it") != std::string::npos,
               "a plane above the goal object's tipping height is a scene warning");
    }
    // The public OMPL layer.
    const ompl::control::SimpleSetupPtr setup = pushplan::makeSetup(pushplan::Planner("scenes/herb_fig1_clutter.yaml"));
    const ompl::base::StateSpacePtr &space = setup->getStateSpace();
    bool sane = true;
    try
    {
        space->sanityChecks();
    }
    catch (const std::exception &e)
    {
        std::cout << e.what() << "\n";
        sane = false;
    }
    expect(sane, "the state space passes OMPL's sanityChecks()");
    try
    {
        pushplan::makeSetup(pushplan::Planner("scenes/dense/scene_00.yaml"))->getStateSpace()->sanityChecks();
    }
    catch (const std::exception &e)
    {
        std::cout << e.what() << "\n";
        sane = false;
    }
    expect(sane, "... and so does a dense scene's (8 objects)");
    const pushplan::StateAccess states(space);
    expect(states.dof() == 7 && states.objectCount() == 4 && states.objectNames()[0] == "green_box",
           "StateAccess knows the scene's joints and objects");
    ompl::base::State *state = space->allocState();
    Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(7, 0.1, 0.7);
    states.setJoints(state, q);
    states.setObjectPose(state, 2, Eigen::Vector3d(0.6, -0.1, 0.5));
    expect(states.joints(state) == q && states.objectPose(state, 2) == Eigen::Vector3d(0.6, -0.1, 0.5),
           "StateAccess reads back what it wrote");
    expect(throwsError([&] { states.objectPose(state, 4); }, "object 4 of 4"), "an object out of range throws");
    space->freeState(state);
    expect(throwsError([] { pushplan::StateAccess(std::make_shared<ompl::base::RealVectorStateSpace>(3)); },
                       "not pushplan's state space"),
           "StateAccess refuses another state space");
    {
        // The validity checker leaves OMPL's bounds to the model: a start state is valid,
        // and a state OMPL's own satisfiesBounds refuses (a joint past its limit, an object
        // past the table's edge, a yaw past +-pi) is never valid.
        const ompl::base::SpaceInformationPtr &si = setup->getSpaceInformation();
        const auto *compound = space->as<ompl::base::CompoundStateSpace>();
        const auto joint_bounds = compound->as<ompl::base::RealVectorStateSpace>(0)->getBounds();
        const auto table = compound->as<ompl::base::SE2StateSpace>(1)->getBounds();
        ompl::base::State *start = space->allocState();
        space->copyState(start, setup->getProblemDefinition()->getStartState(0));
        expect(si->satisfiesBounds(start) && si->isValid(start), "the start state is within bounds and valid");
        ompl::base::State *outside = space->allocState();
        ompl::RNG rng(7);
        int refused = 0;
        const int trials = 300;
        for (int i = 0; i < trials; ++i)
        {
            space->copyState(outside, start);
            const double past = rng.uniformReal(1e-6, 1.0);
            const int which = rng.uniformInt(0, 3);
            if (which == 0)
            {
                Eigen::VectorXd q = states.joints(outside);
                const int j = rng.uniformInt(0, static_cast<int>(states.dof()) - 1);
                q[j] = rng.uniformBool() ? joint_bounds.high[j] + past : joint_bounds.low[j] - past;
                states.setJoints(outside, q);
            }
            else
            {
                const std::size_t object = rng.uniformInt(0, states.objectCount() - 1);
                Eigen::Vector3d pose = states.objectPose(outside, object);
                const int axis = which - 1;  // x, y or yaw
                const double high = axis == 2 ? M_PI : table.high[axis];
                const double low = axis == 2 ? -M_PI : table.low[axis];
                pose[axis] = rng.uniformBool() ? high + past : low - past;
                states.setObjectPose(outside, object, pose);
            }
            refused += (!si->satisfiesBounds(outside) && !si->isValid(outside)) ? 1 : 0;
        }
        space->freeState(outside);
        space->freeState(start);
        expect(refused == trials, "no state outside OMPL's bounds is valid: " + std::to_string(refused) + " of " +
                                      std::to_string(trials) + " refused by both");
    }
    {
        // A grasp goal (goal: {grasp: ...}) is a GoalSampleableRegion sampling the grasp
        // regions through inverse kinematics: most samples lie inside the goal region.
        const ompl::control::SimpleSetupPtr grasping =
            pushplan::makeSetup(pushplan::Planner("scenes/grasp_through_clutter.yaml"));
        const auto *goal = grasping->getGoal()->as<ompl::base::GoalSampleableRegion>();
        ompl::base::State *sample = grasping->getStateSpace()->allocState();
        int inside = 0;
        for (int i = 0; i < 20; ++i)
        {
            goal->sampleGoal(sample);
            inside += goal->isSatisfied(sample) ? 1 : 0;
        }
        grasping->getStateSpace()->freeState(sample);
        expect(inside >= 10, "a grasp goal's samples (IK of its regions) satisfy it: " + std::to_string(inside) + " of 20");
    }
    {
        // Closing the loop through the API (Planner::replan).
        const pushplan::Planner hand("scenes/planar_hand_single_object.yaml");
        pushplan::Options o;
        o.seed = 2;
        o.threads = 1;
        o.shortcut = 0.0;
        const pushplan::Plan plan = hand.solve(o);
        const std::size_t k = plan.controls.size() / 2;
        pushplan::Observation observed{plan.joint_trajectory[k], plan.object_poses[k]};
        const pushplan::Plan same = hand.replan(plan, k, observed, o);
        expect(same.solved && same.replanned && same.replanned->kept && same.replanned->at == k &&
                   same.controls.size() == plan.controls.size() - k,
               "replan keeps the rest of a plan when the world is where the plan said");
        Eigen::Vector3d &box = observed.objects[0];
        move_the_box(box, plan.joint_trajectory[k]);
        const pushplan::Plan moved = hand.replan(plan, k, observed, o);
        const std::size_t rest = plan.controls.size() - k;
        bool same_rest = moved.controls.size() > rest;
        for (std::size_t i = 0; same_rest && i < rest; ++i)
            same_rest = moved.controls[i].ee_velocity == plan.controls[k + i].ee_velocity &&
                        moved.controls[i].steps == plan.controls[k + i].steps;
        expect(moved.solved && moved.replanned && !moved.replanned->kept && moved.replanned->repaired == rest &&
                   same_rest && moved.object_poses.front()[0].isApprox(box, 1e-12),
               "replan repairs the rest of a plan that misses a moved box: the rest kept, an ending searched "
               "from where it ends; the plan starts at the observed state");
        // At the plan's end there is no rest to keep: a new search from the observed state.
        const std::size_t end = plan.controls.size();
        pushplan::Observation after{plan.joint_trajectory[end], plan.object_poses[end]};
        move_the_box(after.objects[0], plan.joint_trajectory[end]);
        const pushplan::Plan anew = hand.replan(plan, end, after, o);
        expect(anew.solved && anew.replanned && !anew.replanned->kept && !anew.replanned->repaired &&
                   anew.object_poses.front()[0].isApprox(after.objects[0], 1e-12),
               "replan searches anew from an observed state with no rest to keep, and starts there");
        pushplan::Observation short_q{plan.joint_trajectory[k].head(2), plan.object_poses[k]};
        expect(throwsError([&] { hand.replan(plan, k, short_q, o); }, "Observation::q"),
               "an observation of the wrong size is refused as pushplan::Error");
        pushplan::Observation inside{plan.joint_trajectory[k], plan.object_poses[k]};
        inside.objects[0].head<2>() = plan.joint_trajectory[k].head<2>();
        expect(throwsError([&] { hand.solveFrom(inside, o); }, "an observation may be off"),
               "an observed box deep inside the hand (further than 2 cm) is no valid start");

        // Closed-loop execution for an application with its own observations
        // (pushplan::Executor). Its "world" here is the model's prediction of each control
        // it plays, except where the test moves the box: where the world is the plan's,
        // the executor plays the plan as it is; where the box is found elsewhere, it
        // re-plans and plays on until the box is in the goal disc (0.85, 0.1), r = 0.1.
        pushplan::ExecutorOptions eo;
        eo.replan_threads = 1;
        // Plays until the executor asks for something else; `now` ends where the world is.
        const auto run = [&](pushplan::Executor &executor, pushplan::Observation &now, std::size_t move_box_at,
                             std::size_t &played) {
            for (played = 0; played < 10 * plan.controls.size() + 10; ++played)
            {
                if (played == move_box_at)
                    move_the_box(now.objects[0], now.q);
                const pushplan::ExecutorStep next = executor.step(now);
                if (next.kind != pushplan::ExecutorStep::Kind::Play)
                    return next;
                if (next.trajectory.q.empty() || !next.trajectory.q.front().isApprox(now.q, 1e-3))
                    return pushplan::ExecutorStep{pushplan::ExecutorStep::Kind::Stopped, {}, {}, {},
                                                  "a trajectory that does not start at the observed joints"};
                now = next.predicted;
            }
            return pushplan::ExecutorStep{pushplan::ExecutorStep::Kind::Stopped, {}, {}, {}, "played on and on"};
        };
        const pushplan::Observation start{plan.joint_trajectory.front(), plan.object_poses.front()};
        pushplan::Executor as_planned(hand, plan, eo);
        std::size_t played = 0;
        pushplan::Observation now = start;
        const pushplan::ExecutorStep played_out = run(as_planned, now, std::numeric_limits<std::size_t>::max(), played);
        const pushplan::ExecutorReport as_is = as_planned.report();
        expect(plan.solved && played_out.kind == pushplan::ExecutorStep::Kind::Finished && played == plan.controls.size() &&
                   as_is.controls_played == played && as_is.replans == 0 && as_is.failed_replans == 0 &&
                   as_is.kept == played + 1,
               "an Executor plays a plan as it is while the world is where the plan said");
        pushplan::Executor off_its_way(hand, plan, eo);
        now = start;
        const pushplan::ExecutorStep replanned = run(off_its_way, now, k, played);
        const pushplan::ExecutorReport report = off_its_way.report();
        const bool in_disc = (now.objects[0].head<2>() - Eigen::Vector2d(0.85, 0.1)).norm() < 0.1;
        expect(replanned.kind == pushplan::ExecutorStep::Kind::Finished && in_disc && report.replans >= 1 &&
                   report.replan_latencies.size() == report.replans + report.legs && report.search_time > 0.0,
               "an Executor re-plans where the box is found off its way, and plays on until the box is in the "
               "goal disc (" +
                   std::to_string(report.replans) + " re-plans, " + std::to_string(played) + " controls, the plan " +
                   std::to_string(plan.controls.size()) + ")");
        expect(throwsError(
                   [&] {
                       pushplan::ExecutorOptions bad = eo;
                       bad.replan_time = -1.0;
                       pushplan::Executor(hand, plan, bad);
                   },
                   "ExecutorOptions::replan_time: must be in (0, 86400]"),
               "an Executor refuses an option out of its limit, naming it");
        expect(throwsError([&] { pushplan::Executor(hand, pushplan::Plan{}, eo); }, "not solved"),
               "an Executor refuses an unsolved plan");
        pushplan::Executor replay(hand, plan, eo);
        expect(throwsError([&] { replay.step(short_q); }, "Observation::q"),
               "an Executor refuses an observation of the wrong size as pushplan::Error");
        const pushplan::ExecutorStep refused = replay.step(inside);
        expect(refused.kind == pushplan::ExecutorStep::Kind::Stopped &&
                   refused.why.find("no valid start") != std::string::npos && replay.report().stopped == refused.why,
               "an Executor stops, saying why, on an observation that is no valid start");
    }
    {
        // A Planner reads its scene file once, when it is made: with the file gone, it still
        // plans and re-plans, and its searches (each on a copy of the scene read then)
        // plan bit for bit what a Planner of the file in place plans.
        const std::filesystem::path copy =
            std::filesystem::temp_directory_path() / ("pushplan-read-once-" + std::to_string(getpid()) + ".yaml");
        std::filesystem::copy_file("scenes/planar_hand_single_object.yaml", copy,
                                   std::filesystem::copy_options::overwrite_existing);
        const pushplan::Planner read_once(copy.string());
        std::filesystem::remove(copy);
        pushplan::Options o;
        o.seed = 3;
        o.threads = 2;
        o.shortcut = 0.0;
        const pushplan::Plan plan = read_once.solve(o);
        const pushplan::Plan in_place = pushplan::Planner("scenes/planar_hand_single_object.yaml").solve(o);
        bool same = plan.solved && plan.controls.size() == in_place.controls.size();
        for (std::size_t i = 0; same && i < plan.controls.size(); ++i)
            same = plan.controls[i].ee_velocity == in_place.controls[i].ee_velocity &&
                   plan.controls[i].steps == in_place.controls[i].steps;
        const std::size_t end = plan.controls.size();
        pushplan::Observation after{plan.joint_trajectory[end], plan.object_poses[end]};
        // The box found 5 cm further from the hand and 15 cm aside, out of the goal disc.
        Eigen::Vector3d &box = after.objects[0];
        box.head<2>() += 0.05 * (box.head<2>() - after.q.head<2>()).normalized();
        box.y() -= 0.15;
        const pushplan::Plan again = read_once.replan(plan, end, after, o);
        expect(same && again.solved && again.replanned && !again.replanned->kept,
               "a Planner reads its scene file once: with the file removed it plans (as a Planner of the "
               "file in place does, bit for bit, on two threads) and re-plans");
        // Push KPIECE on two threads: one search, its extensions on three lanes; one
        // thread has none.
        pushplan::Options one = o;
        one.threads = 1;
        one.time_limit = 0.01;
        expect(plan.threads == 2 && plan.lanes == 3 && read_once.solve(one).lanes == 0,
               "Plan::lanes: the lanes the one search ran on (three on two threads, none on one)");
    }
    {
        // Seeded fuzzing of Options through Planner::solve: every count, duration and rate
        // near or past its limit. A case either plans (its values within the limits) or
        // throws pushplan::Error naming an Options field; nothing else leaves, and no case
        // runs past its time limit (a tenth of a second when allowed) by more than a second.
        const pushplan::Planner hand("scenes/planar_hand_single_object.yaml");
        std::uint64_t state = 59;
        const auto draw = [&](std::size_t n) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            return static_cast<std::size_t>((state >> 33) % n);
        };
        const unsigned counts[] = {0u, 1u, 2u, 65u, 257u, 1001u, 10001u, 1000000000u, UINT_MAX};
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const double inf = std::numeric_limits<double>::infinity();
        // No duration allowed here is long: a case that plans plans for a tenth of a second.
        const double times[] = {nan, inf, -1.0, 0.0, 0.1, 86401.0};
        const double shares[] = {nan, -0.5, 0.0, 0.5, 1.0, 1.5};
        unsigned planned = 0, refused = 0, other = 0, slow = 0;
        for (int c = 0; c < 200; ++c)
        {
            pushplan::Options o;
            o.seed = 1;
            // Each value extreme one time in eight, else an ordinary one: some cases plan.
            const auto count = [&](unsigned ordinary) { return draw(8) == 0 ? counts[draw(9)] : ordinary; };
            const auto seconds = [&](double ordinary) { return draw(8) == 0 ? times[draw(6)] : ordinary; };
            const auto share = [&](double ordinary) { return draw(8) == 0 ? shares[draw(6)] : ordinary; };
            o.k = count(3);
            o.threads = std::min(count(1), 257u);
            o.robust_trials = count(5);
            o.robust_particles = std::min(count(0), 65u);
            o.time_limit = seconds(0.1);
            o.shortcut = seconds(0.0);
            o.robust_shortcut = seconds(0.0);
            o.goal_bias = share(0.05);
            o.robust_rate = share(0.95);
            const auto started = std::chrono::steady_clock::now();
            try
            {
                hand.solve(o);
                ++planned;
            }
            catch (const pushplan::Error &e)
            {
                (std::string(e.what()).rfind("Options::", 0) == 0 ? refused : other) += 1;
                if (std::string(e.what()).rfind("Options::", 0) != 0)
                    std::cout << "  fuzzed options, case " << c << ": " << e.what() << "\n";
            }
            catch (...)
            {
                ++other;
            }
            if (const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
                wall > 1.1)
            {
                ++slow;
                std::cout << "  fuzzed options, case " << c << ": " << wall << " s\n";
            }
        }
        std::cout << "fuzzed Options: " << planned << " planned, " << refused << " refused, " << other
                  << " other failures, " << slow << " slow\n";
        expect(other == 0 && refused > 100 && planned > 0 && slow == 0,
               "200 fuzzed Options: each plans or throws pushplan::Error naming its field, within its time");
    }
    return failures == 0 ? 0 : 1;
}
