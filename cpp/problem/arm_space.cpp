#include "pushplan/cpp/problem/arm_space.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <algorithm>

namespace ob = ompl::base;

namespace pushplan::detail
{
    namespace
    {
        const double *joints(const ob::State *arm)
        {
            return arm->as<ob::RealVectorStateSpace::StateType>()->values;
        }

        /// Arm-space states are valid when the full state (objects where they are) is.
        class ArmValidity : public ob::StateValidityChecker
        {
        public:
            ArmValidity(const ob::SpaceInformationPtr &si, const ModelHandle &model, std::shared_ptr<FlatState> context)
              : ob::StateValidityChecker(si),
                dof_(model.info().dof),
                validity_(bridge::ValidityChecker::make(model.problem())),
                context_(std::move(context))
            {
            }
            bool isValid(const ob::State *state) const override
            {
                std::copy(joints(state), joints(state) + dof_, context_->begin());
                return validity_->is_valid(slice(*context_), {});
            }

        private:
            std::size_t dof_;
            rust::Box<bridge::ValidityChecker> validity_;
            std::shared_ptr<FlatState> context_;
        };

        /// Arm-space motions are Transit lines, checked by the model at its resolution.
        class TransitMotions : public ob::MotionValidator
        {
        public:
            TransitMotions(const ob::SpaceInformationPtr &si, const ModelHandle &model, std::shared_ptr<FlatState> context)
              : ob::MotionValidator(si),
                dof_(model.info().dof),
                darrt_(bridge::Darrt::make(model.problem())),
                context_(std::move(context))
            {
            }
            bool checkMotion(const ob::State *s1, const ob::State *s2) const override
            {
                const std::size_t dof = dof_;
                from_ = *context_;
                to_ = *context_;
                std::copy(joints(s1), joints(s1) + dof, from_.begin());
                std::copy(joints(s2), joints(s2) + dof, to_.begin());
                const bool valid = darrt_->transit(slice(from_), slice(to_));
                (valid ? valid_ : invalid_)++;
                return valid;
            }
            // RRT-Connect asks only the two-state form; the last valid state is not
            // located, so the answer is the (conservative) start of the motion.
            bool checkMotion(const ob::State *s1, const ob::State *s2,
                             std::pair<ob::State *, double> &last_valid) const override
            {
                if (checkMotion(s1, s2))
                    return true;
                if (last_valid.first != nullptr)
                    si_->copyState(last_valid.first, s1);
                last_valid.second = 0.0;
                return false;
            }

        private:
            std::size_t dof_;
            rust::Box<bridge::Darrt> darrt_;
            std::shared_ptr<FlatState> context_;
            mutable FlatState from_, to_;
        };

        /// Uniform joint samples from a given seed.
        class SeededJointSampler : public ob::RealVectorStateSampler
        {
        public:
            SeededJointSampler(const ob::StateSpace *space, std::uint_fast32_t seed)
              : ob::RealVectorStateSampler(space)
            {
                rng_.setLocalSeed(seed);
            }
        };
    }  // namespace

    ArmSpace::ArmSpace(const ModelHandle &model)
      : dof_(model.info().dof),
        context_(std::make_shared<FlatState>(FlatLayout{model.info().dof, model.info().objects}.size()))
    {
        const bridge::SceneInfo &info = model.info();
        auto space = std::make_shared<ob::RealVectorStateSpace>(info.dof);
        ob::RealVectorBounds bounds(info.dof);
        for (std::size_t i = 0; i < info.dof; ++i)
        {
            bounds.setLow(i, info.joint_lower[i]);
            bounds.setHigh(i, info.joint_upper[i]);
        }
        space->setBounds(bounds);
        std::shared_ptr<std::uint_fast32_t> counter = sampler_seed_;
        space->setStateSamplerAllocator([counter](const ob::StateSpace *s) {
            return std::make_shared<SeededJointSampler>(s, (*counter)++);
        });
        si_ = std::make_shared<ob::SpaceInformation>(space);
        si_->setStateValidityChecker(std::make_shared<ArmValidity>(si_, model, context_));
        si_->setMotionValidator(std::make_shared<TransitMotions>(si_, model, context_));
        si_->setup();
    }

    void ArmSpace::withJoints(const ob::State *arm, FlatState &full) const
    {
        std::copy(joints(arm), joints(arm) + dof_, full.begin());
    }

    void ArmSpace::toArm(const FlatState &full, ob::State *arm) const
    {
        double *q = arm->as<ob::RealVectorStateSpace::StateType>()->values;
        std::copy(full.begin(), full.begin() + dof_, q);
    }
}  // namespace pushplan::detail
