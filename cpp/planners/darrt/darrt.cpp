#include "pushplan/cpp/planners/darrt/darrt.h"

#include "pushplan/cpp/problem/problem.h"
#include "pushplan/cpp/problem/sampling.h"
#include "pushplan/pushplan.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/goals/GoalRegion.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <cmath>
#include <limits>
#include <numeric>

namespace ob = ompl::base;
namespace oc = ompl::control;
namespace og = ompl::geometric;

namespace pushplan::detail
{
    namespace
    {
        rust::Slice<const double> view(const double *data, std::size_t size)
        {
            return rust::Slice<const double>(data, size);
        }

        class SeededRRTConnect : public og::RRTConnect
        {
        public:
            SeededRRTConnect(const ob::SpaceInformationPtr &si, std::uint_fast32_t seed) : og::RRTConnect(si)
            {
                rng_.setLocalSeed(seed);
            }
        };
    }  // namespace

    PrimitivePath::PrimitivePath(const oc::SpaceInformationPtr &si, const ModelHandle &model,
                                 const std::vector<double> &states, const std::vector<std::int64_t> &held,
                                 bridge::PrimitiveCheck report)
      : oc::PathControl(si),
        darrt_(bridge::Darrt::make(model.problem())),
        flat_(states),
        held_(held),
        report_(std::move(report))
    {
        const StateView &view = *model.view();
        const std::size_t n = view.stateSize();
        ob::State *state = si->allocState();
        oc::Control *control = si->allocControl();
        si->nullControl(control);
        FlatState buffer(n);
        for (std::size_t at = 0; at < flat_.size(); at += n)
        {
            std::copy(flat_.begin() + at, flat_.begin() + at + n, buffer.begin());
            view.write(buffer, state);
            // One propagation step per placeholder control: OMPL's interpolation then
            // keeps the primitive states instead of propagating the placeholders.
            if (at == 0)
                append(state);
            else
                append(state, control, si->getPropagationStepSize());
        }
        si->freeControl(control);
        si->freeState(state);
    }

    double PrimitivePath::length() const
    {
        return std::accumulate(report_.durations.begin(), report_.durations.end(), 0.0);
    }

    bool PrimitivePath::check() const
    {
        return darrt_->check(slice(flat_), slice(held_)).valid;
    }

    ArmTransit::ArmTransit(const ModelHandle &model, double time_cap) : space_(model), time_cap_(time_cap)
    {
    }

    bool ArmTransit::plan(const FlatState &from, const FlatState &to, const ob::PlannerTerminationCondition &ptc,
                          std::uint_fast32_t seed, std::vector<FlatState> &motion)
    {
        space_.context() = from;
        space_.seedSamplers(subSeed(seed, 1));
        const ob::SpaceInformationPtr &si = space_.si();
        ob::ScopedState<> start(si), goal(si);
        space_.toArm(from, start.get());
        space_.toArm(to, goal.get());
        auto pdef = std::make_shared<ob::ProblemDefinition>(si);
        pdef->setStartAndGoalStates(start, goal);
        auto planner = std::make_shared<SeededRRTConnect>(si, subSeed(seed, 0));
        planner->setProblemDefinition(pdef);
        planner->setup();
        const ob::PlannerStatus status =
            planner->solve(ob::plannerOrTerminationCondition(ptc, ob::timedPlannerTerminationCondition(time_cap_)));
        if (status != ob::PlannerStatus::EXACT_SOLUTION)
            return false;
        const auto &path = *pdef->getSolutionPath()->as<og::PathGeometric>();
        for (std::size_t k = 1; k < path.getStateCount(); ++k)
        {
            FlatState waypoint = from;
            space_.withJoints(path.getState(k), waypoint);
            motion.push_back(std::move(waypoint));
        }
        // The goal tree is rooted at the goal itself, so the path ends exactly there.
        return !motion.empty() && motion.back() == to;
    }

    Darrt::Darrt(const oc::SpaceInformationPtr &si, ModelHandlePtr model, std::uint_fast32_t seed)
      : ob::Planner(si, "DARRT"),
        model_(std::move(model)),
        view_(model_->view()),
        darrt_(bridge::Darrt::make(model_->problem())),
        validity_(bridge::ValidityChecker::make(model_->problem())),
        transit_(*model_, 15.0)
    {
        rng_.setLocalSeed(seed);
        goal_bias_ = view_->info().planner.goal_bias;
        const std::size_t dof = view_->info().dof;
        arms_.setDistanceFunction([this, dof](int a, int b) {
            const FlatState &x = a < 0 ? arm_query_ : nodes_[a].state;
            const FlatState &y = b < 0 ? arm_query_ : nodes_[b].state;
            double d = 0.0;
            for (std::size_t i = 0; i < dof; ++i)
                d += (x[i] - y[i]) * (x[i] - y[i]);
            return std::sqrt(d);
        });
        for (std::size_t i = 0; i < view_->info().objects; ++i)
        {
            auto places = std::make_unique<ObjectPlaces>();
            ObjectPlaces *p = places.get();
            p->tree.setDistanceFunction([p](int a, int b) {
                const std::array<double, 2> &x = a < 0 ? p->query : p->xy[a];
                const std::array<double, 2> &y = b < 0 ? p->query : p->xy[b];
                return std::hypot(x[0] - y[0], x[1] - y[1]);
            });
            places_.push_back(std::move(places));
        }

        specs_.approximateSolutions = false;
        specs_.directed = true;
        declareParam<double>("goal_bias", this, &Darrt::setGoalBias, &Darrt::getGoalBias, "0.:.05:1.");
        declareParam<double>("transit_time", this, &Darrt::setTransitTime, &Darrt::getTransitTime, "0.:1.:60.");
        declareParam<double>("pick_place", this, &Darrt::setPickPlace, &Darrt::getPickPlace, "0.:.1:1.");
    }

    Darrt::~Darrt()
    {
        clear();
    }

    void Darrt::reseed(std::uint_fast32_t seed)
    {
        rng_.setLocalSeed(seed);
    }

    void Darrt::clear()
    {
        ob::Planner::clear();
        for (Node &node : nodes_)
            si_->freeState(node.ompl_state);
        nodes_.clear();
        arms_.clear();
        for (auto &places : places_)
        {
            places->tree.clear();
            places->xy.clear();
            places->nodes.clear();
            places->id.clear();
        }
    }

    int Darrt::addNode(int parent, std::vector<FlatState> motion, std::vector<std::int64_t> held)
    {
        if (held.empty())
            held.assign(motion.size(), -1);
        Node node;
        node.state = motion.back();
        node.ompl_state = si_->allocState();
        view_->write(node.state, node.ompl_state);
        node.parent = parent;
        node.motion = std::move(motion);
        node.held = std::move(held);
        nodes_.push_back(std::move(node));
        const int index = static_cast<int>(nodes_.size()) - 1;
        arms_.add(index);
        const FlatState &state = nodes_.back().state;
        const FlatLayout layout = view_->flat();
        for (std::size_t i = 0; i < places_.size(); ++i)
        {
            ObjectPlaces &places = *places_[i];
            const std::size_t at = layout.object(i);
            const std::array<double, 2> xy{state[at], state[at + 1]};
            const auto [it, is_new] = places.id.emplace(xy, static_cast<int>(places.xy.size()));
            if (is_new)
            {
                places.xy.push_back(xy);
                places.nodes.emplace_back();
                places.tree.add(it->second);
            }
            places.nodes[it->second].push_back(index);
        }
        return index;
    }

    bool Darrt::rrtTransit(int from, const FlatState &to, const ob::PlannerTerminationCondition &ptc,
                           std::vector<FlatState> &motion)
    {
        const auto seed = static_cast<std::uint64_t>(rng_.uniformInt(0, std::numeric_limits<int>::max()));
        return transit_.plan(nodes_[from].state, to, ptc, subSeed(seed, transit_calls_++), motion);
    }

    int Darrt::extendArm(const ob::PlannerTerminationCondition &ptc)
    {
        const bridge::SceneInfo &info = view_->info();
        FlatState q(info.dof);
        sampleJoints(info, rng_, q.data());
        const int nearest = nearestArm(q);
        FlatState target = nodes_[nearest].state;
        std::copy(q.begin(), q.end(), target.begin());
        if (!validity_->is_valid(slice(target), {}))
            return -1;
        // Transit if the straight line is free, else RRTTransit.
        std::vector<FlatState> motion;
        if (darrt_->transit(slice(nodes_[nearest].state), slice(target)))
            motion.push_back(target);
        else if (!rrtTransit(nearest, target, ptc, motion))
            return -1;
        return addNode(nearest, std::move(motion));
    }

    int Darrt::extendObject(int object, const ob::PlannerTerminationCondition &ptc)
    {
        const bridge::SceneInfo &info = view_->info();
        const bool toward_goal = object == info.goal_object && rng_.uniform01() < goal_bias_;
        const auto [x, y] = toward_goal ? sampleInGoalDisc(info, rng_) : sampleOnTable(info, rng_);
        const std::array<double, 3> target{x, y, sampleYaw(rng_)};

        const int nearest = nearestObject(object, {target[0], target[1]});
        if (pick_place_ > 0.0 && rng_.uniform01() < pick_place_)
        {
            const int placed = pickPlace(nearest, object, target);
            if (placed >= 0)
                return placed;
        }
        const rust::Slice<const double> target_pose = view(target.data(), 3);
        FlatState caged(view_->stateSize());
        if (!darrt_->approach(slice(nodes_[nearest].state), object, target_pose,
                                            rust::Slice<double>(caged.data(), caged.size())))
            return -1;
        // The paper: "the RRTTransit primitive is first applied to move the manipulator to
        // the object".
        std::vector<FlatState> motion;
        if (caged != nodes_[nearest].state && !rrtTransit(nearest, caged, ptc, motion))
            return -1;
        const rust::Vec<double> carried = darrt_->carry(slice(caged), object, target_pose);
        if (carried.empty())
            return -1;
        const std::size_t n = view_->stateSize();
        for (std::size_t k = 0; k < carried.size(); k += n)
            motion.emplace_back(carried.begin() + k, carried.begin() + k + n);
        return addNode(nearest, std::move(motion));
    }

    int Darrt::pickPlace(int from, int object, const std::array<double, 3> &target)
    {
        const auto seed = static_cast<std::uint64_t>(rng_.uniformInt(0, std::numeric_limits<int>::max()));
        const bridge::HeldStates placed =
            darrt_->pick_place(slice(nodes_[from].state), object, view(target.data(), 3), seed);
        if (placed.held.empty())
            return -1;
        const std::size_t n = view_->stateSize();
        std::vector<FlatState> motion;
        for (std::size_t k = 0; k < placed.states.size(); k += n)
            motion.emplace_back(placed.states.begin() + k, placed.states.begin() + k + n);
        return addNode(from, std::move(motion), std::vector<std::int64_t>(placed.held.begin(), placed.held.end()));
    }

    int Darrt::nearestArm(const FlatState &q) const
    {
        arm_query_ = q;
        return arms_.nearest(-1);
    }

    int Darrt::nearestObject(int object, const std::array<double, 2> &xy)
    {
        // The nearest place, then one of its nodes drawn uniformly: the arm configurations
        // the tree has reached with the object there all serve as starts of a Push.
        ObjectPlaces &places = *places_[static_cast<std::size_t>(object)];
        places.query = xy;
        const std::vector<int> &there = places.nodes[places.tree.nearest(-1)];
        if (there.size() == 1)
            return there.front();
        return there[rng_.uniformInt(0, static_cast<int>(there.size()) - 1)];
    }

    ob::PlannerStatus Darrt::solve(const ob::PlannerTerminationCondition &ptc)
    {
        checkValidity();
        const bridge::SceneInfo &info = view_->info();
        if (nodes_.empty())
        {
            const ob::State *start = pis_.nextStart();
            if (start == nullptr)
                return ob::PlannerStatus::INVALID_START;
            FlatState flat;
            view_->read(start, flat);
            addNode(-1, {flat});
            if (reachesGoal(start))
                return report(0);
        }
        // The kinds of sample: the arm, the goal object, another object (if any).
        std::vector<int> others;
        for (int i = 0; i < static_cast<int>(info.objects); ++i)
            if (i != info.goal_object)
                others.push_back(i);
        const int kinds = 1 + (info.goal_object >= 0 ? 1 : 0) + (others.empty() ? 0 : 1);
        while (!ptc)
        {
            int kind = rng_.uniformInt(0, kinds - 1);
            if (kind == 1 && info.goal_object < 0)
                kind = 2;
            int added = -1;
            if (kind == 0)
                added = extendArm(ptc);
            else if (kind == 1)
                added = extendObject(static_cast<int>(info.goal_object), ptc);
            else
                added = extendObject(others[rng_.uniformInt(0, static_cast<int>(others.size()) - 1)], ptc);
            if (added >= 0 && reachesGoal(nodes_[added].ompl_state))
                return report(added);
        }
        return ob::PlannerStatus::TIMEOUT;
    }

    ob::PlannerStatus Darrt::report(int goal_node)
    {
        std::vector<int> chain;
        for (int n = goal_node; n >= 0; n = nodes_[n].parent)
            chain.push_back(n);
        std::vector<double> states(nodes_[0].state);
        std::vector<std::int64_t> held{-1};
        for (auto it = chain.rbegin() + 1; it != chain.rend(); ++it)
        {
            for (const FlatState &s : nodes_[*it].motion)
                states.insert(states.end(), s.begin(), s.end());
            held.insert(held.end(), nodes_[*it].held.begin(), nodes_[*it].held.end());
        }
        bridge::PrimitiveCheck check = darrt_->check(slice(states), slice(held));
        if (!check.valid || !check.goal_reached)
        {
            // A primitive the model accepted fails its own check: a bug, never a plan.
            OMPL_ERROR("%s: the path fails its check: %s", getName().c_str(),
                       check.valid ? "the goal is not reached" : std::string(check.message).c_str());
            return ob::PlannerStatus::CRASH;
        }
        auto path = std::make_shared<PrimitivePath>(std::static_pointer_cast<oc::SpaceInformation>(si_), *model_,
                                                    states, held, std::move(check));
        pdef_->addSolutionPath(path, false, 0.0, getName());
        return ob::PlannerStatus::EXACT_SOLUTION;
    }

    bool Darrt::reachesGoal(const ob::State *state) const
    {
        // The goal's signed distance (PushGoal: the model's), zero or negative inside.
        return pdef_->getGoal()->as<ob::GoalRegion>()->distanceGoal(state) <= 0.0;
    }

    void Darrt::getPlannerData(ob::PlannerData &data) const
    {
        ob::Planner::getPlannerData(data);
        for (const Node &node : nodes_)
        {
            if (node.parent < 0)
                data.addStartVertex(ob::PlannerDataVertex(node.ompl_state));
            else
                data.addEdge(ob::PlannerDataVertex(nodes_[node.parent].ompl_state),
                             ob::PlannerDataVertex(node.ompl_state));
        }
    }
}  // namespace pushplan::detail
