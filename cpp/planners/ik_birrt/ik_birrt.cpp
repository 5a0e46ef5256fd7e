#include "pushplan/cpp/planners/ik_birrt/ik_birrt.h"

#include "pushplan/pushplan.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/tools/config/SelfConfig.h>

#include <algorithm>
#include <limits>
#include <utility>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace pushplan::detail
{
    GraspGoal::GraspGoal(const ArmSpace &space, const ModelHandle &model, const FlatState &from, std::size_t object,
                         std::uint64_t seed)
      : ob::GoalSampleableRegion(space.si()), space_(space), grasping_(bridge::Grasping::make(model.problem())), from_(from),
        object_(object), seed_(seed), scratch_(from)
    {
        // Inside a region within the model's tolerance (robot::wgr::GRASP_TOLERANCE).
        setThreshold(1e-3);
    }

    bool GraspGoal::trySample(ob::State *state) const
    {
        const rust::Vec<double> q = grasping_->sample(slice(from_), object_, seed_++);
        if (q.empty())
            return false;
        std::copy(q.begin(), q.end(), scratch_.begin());
        space_.toArm(scratch_, state);
        return true;
    }

    void GraspGoal::sampleGoal(ob::State *state) const
    {
        for (int tries = 0; tries < 10000; ++tries)
            if (trySample(state))
                return;
        throw Error("no valid configuration found in the grasp regions of object " + std::to_string(object_));
    }

    unsigned int GraspGoal::maxSampleCount() const
    {
        return std::numeric_limits<unsigned int>::max();
    }

    double GraspGoal::distanceGoal(const ob::State *state) const
    {
        scratch_ = from_;
        space_.withJoints(state, scratch_);
        return grasping_->distance(slice(scratch_), object_);
    }

    IkBiRrt::IkBiRrt(const ob::SpaceInformationPtr &si, std::uint_fast32_t seed) : ob::Planner(si, "IK-BiRRT")
    {
        rng_.setLocalSeed(seed);
        specs_.recognizedGoal = ob::GOAL_SAMPLEABLE_REGION;
        specs_.directed = true;
        declareParam<double>("sample_probability", this, &IkBiRrt::setSampleProbability,
                             &IkBiRrt::getSampleProbability, "0.:.05:1.");
        declareParam<double>("range", this, &IkBiRrt::setRange, &IkBiRrt::getRange, "0.:1.:10.");
    }

    IkBiRrt::~IkBiRrt()
    {
        freeMotions();
    }

    void IkBiRrt::setup()
    {
        ob::Planner::setup();
        ompl::tools::SelfConfig(si_, getName()).configurePlannerRange(range_);
        // Linear search: deterministic, and the trees of a reach stay small.
        start_tree_ = std::make_shared<ompl::NearestNeighborsLinear<Motion *>>();
        goal_tree_ = std::make_shared<ompl::NearestNeighborsLinear<Motion *>>();
        auto metric = [this](const Motion *a, const Motion *b) { return si_->distance(a->state, b->state); };
        start_tree_->setDistanceFunction(metric);
        goal_tree_->setDistanceFunction(metric);
    }

    void IkBiRrt::clear()
    {
        ob::Planner::clear();
        freeMotions();
        if (start_tree_)
            start_tree_->clear();
        if (goal_tree_)
            goal_tree_->clear();
        sampler_.reset();
        goal_samples_ = 0;
    }

    void IkBiRrt::freeMotions()
    {
        for (Motion *m : motions_)
        {
            si_->freeState(m->state);
            delete m;
        }
        motions_.clear();
    }

    std::size_t IkBiRrt::treeSize() const
    {
        return (start_tree_ ? start_tree_->size() : 0) + (goal_tree_ ? goal_tree_->size() : 0);
    }

    IkBiRrt::Motion *IkBiRrt::add(Tree &tree, ob::State *state, Motion *parent)
    {
        auto *m = new Motion{state, parent};
        motions_.push_back(m);
        tree->add(m);
        return m;
    }

    IkBiRrt::Growth IkBiRrt::grow(Tree &tree, const ob::State *target, Motion *&last)
    {
        Motion query{const_cast<ob::State *>(target), nullptr};
        last = tree->nearest(&query);
        bool advanced = false;
        while (true)
        {
            const double d = si_->distance(last->state, target);
            if (d <= 1e-12)
                return Growth::Reached;
            ob::State *next = si_->allocState();
            const bool whole = d <= range_;
            if (whole)
                si_->copyState(next, target);
            else
                si_->getStateSpace()->interpolate(last->state, target, range_ / d, next);
            if (!si_->isValid(next) || !si_->checkMotion(last->state, next))
            {
                si_->freeState(next);
                return advanced ? Growth::Advanced : Growth::Trapped;
            }
            last = add(tree, next, last);
            advanced = true;
            if (whole)
                return Growth::Reached;
        }
    }

    ob::PlannerStatus IkBiRrt::solve(const ob::PlannerTerminationCondition &ptc)
    {
        checkValidity();
        auto *goal = dynamic_cast<ob::GoalSampleableRegion *>(pdef_->getGoal().get());
        if (goal == nullptr)
            return ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE;
        auto *grasp = dynamic_cast<GraspGoal *>(goal);
        while (const ob::State *start = pis_.nextStart())
        {
            ob::State *s = si_->allocState();
            si_->copyState(s, start);
            add(start_tree_, s, nullptr);
        }
        if (start_tree_->size() == 0)
            return ob::PlannerStatus::INVALID_START;
        if (!sampler_)
            sampler_ = si_->allocStateSampler();

        // One sample of the goal regions, as a new root of the goal tree.
        auto addGoalSample = [&] {
            ob::State *s = si_->allocState();
            const bool found = grasp != nullptr ? grasp->trySample(s) : (goal->sampleGoal(s), si_->isValid(s));
            if (!found)
            {
                si_->freeState(s);
                return;
            }
            add(goal_tree_, s, nullptr);
            ++goal_samples_;
        };

        Tree *a = &start_tree_, *b = &goal_tree_;
        ob::State *random = si_->allocState();
        std::pair<Motion *, Motion *> meeting{nullptr, nullptr};
        while (!ptc && meeting.first == nullptr)
        {
            if (goal_tree_->size() == 0 || rng_.uniform01() < p_sample_)
            {
                addGoalSample();
                continue;
            }
            sampler_->sampleUniform(random);
            Motion *reached_a = nullptr, *reached_b = nullptr;
            if (grow(*a, random, reached_a) != Growth::Trapped &&
                grow(*b, reached_a->state, reached_b) == Growth::Reached)
                meeting = a == &start_tree_ ? std::make_pair(reached_a, reached_b) :
                                              std::make_pair(reached_b, reached_a);
            std::swap(a, b);
        }
        si_->freeState(random);
        if (meeting.first == nullptr)
            return ob::PlannerStatus::TIMEOUT;

        // The start tree's branch from its root, then the goal tree's down to its root.
        std::vector<const ob::State *> states;
        for (Motion *m = meeting.first; m != nullptr; m = m->parent)
            states.push_back(m->state);
        std::reverse(states.begin(), states.end());
        for (Motion *m = meeting.second->parent; m != nullptr; m = m->parent)
            states.push_back(m->state);
        auto path = std::make_shared<og::PathGeometric>(si_);
        for (const ob::State *s : states)
            path->append(s);
        pdef_->addSolutionPath(path, false, 0.0, getName());
        return ob::PlannerStatus::EXACT_SOLUTION;
    }
}  // namespace pushplan::detail
