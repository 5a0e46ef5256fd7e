#include "pushplan/cpp/problem/goal.h"

#include "pushplan/cpp/problem/sampling.h"
#include "pushplan/cpp/problem/state_space.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pushplan::detail
{
    PushGoal::PushGoal(const ompl::base::SpaceInformationPtr &si, ModelHandlePtr model, std::uint_fast32_t seed)
      : ompl::base::GoalSampleableRegion(si), model_(std::move(model))
    {
        rng_.setLocalSeed(seed);
        setThreshold(0.0);
    }

    // Signed: negative inside the region. OMPL's GoalRegion accepts distance < threshold
    // (here 0), so a state OMPL accepts is one the model accepts (distance <= 0) too.
    double PushGoal::distanceGoal(const ompl::base::State *state) const
    {
        return model_->goalDistance(state);
    }

    void PushGoal::sampleGoal(ompl::base::State *state) const
    {
        // A target for the tree, like the state sampler's: the goal object in its disc (or
        // the goal configuration), everything else uniform, valid or not. (Drawing until
        // valid took 60 % of the time in dense clutter: BENCHMARKS.md.)
        const auto &info = model_->info();
        if (info.grasp_object >= 0 && sampleGrasp(state))
            return;
        PushStateSampler::sampleRaw(info, rng_, buffer_);
        if (info.goal_object >= 0)
        {
            const std::size_t at = FlatLayout{info.dof, info.objects}.object(static_cast<std::size_t>(info.goal_object));
            const auto [x, y] = sampleInGoalDisc(info, rng_);
            buffer_[at] = x;
            buffer_[at + 1] = y;
        }
        else
        {
            std::copy(info.goal_configuration.begin(), info.goal_configuration.end(), buffer_.begin());
        }
        model_->view()->pinClutter(buffer_);
        model_->view()->write(buffer_, state);
    }

    bool PushGoal::sampleGrasp(ompl::base::State *state) const
    {
        // The objects where they start, the arm at an IK solution of a grasp region there
        // (one try; the model's inverse kinematics may find none).
        const auto &info = model_->info();
        const std::uint64_t seed = (static_cast<std::uint64_t>(rng_.uniformInt(0, 0x7fffffff)) << 31) |
                                   static_cast<std::uint64_t>(rng_.uniformInt(0, 0x7fffffff));
        const rust::Vec<double> q =
            model_->goal().sample_grasp(rust::Slice<const double>(info.start.data(), info.start.size()),
                                        static_cast<std::size_t>(info.grasp_object), seed);
        if (q.empty())
            return false;
        buffer_.assign(info.start.begin(), info.start.end());
        std::copy(q.begin(), q.end(), buffer_.begin());
        model_->view()->write(buffer_, state);
        return true;
    }

    unsigned int PushGoal::maxSampleCount() const
    {
        return std::numeric_limits<unsigned int>::max();
    }
}  // namespace pushplan::detail
