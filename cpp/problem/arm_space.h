// The arm's joint space as an OMPL geometric space, every object a static obstacle where
// a given state has it: shared by DARRT's RRTTransit and IK-BiRRT.
#pragma once

#include "pushplan/cpp/problem/model_handle.h"

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/State.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace pushplan::detail
{
    /// A flat state (the bridge's layout: joints, then x, y, yaw per object).
    using FlatState = std::vector<double>;

    /// Joint-space states are valid when the full state (objects where `context` has
    /// them) is; motions are checked as DARRT's Transit lines by the model.
    class ArmSpace
    {
    public:
        /// The arm space of `model`'s problem (with a validity checker and DARRT's
        /// Transit of its own).
        explicit ArmSpace(const ModelHandle &model);

        const ompl::base::SpaceInformationPtr &si() const { return si_; }
        /// The full state whose joints the arm space's states replace.
        FlatState &context() { return *context_; }
        /// Seeds the next state sampler drawn from the space (OMPL's default sampler
        /// draws from its global seed sequence; ours from this seed on).
        void seedSamplers(std::uint_fast32_t seed) { *sampler_seed_ = seed; }

        /// Writes an arm-space state's joints into a full state.
        void withJoints(const ompl::base::State *arm, FlatState &full) const;
        /// Writes a full state's joints into an arm-space state.
        void toArm(const FlatState &full, ompl::base::State *arm) const;

    private:
        std::size_t dof_;
        std::shared_ptr<FlatState> context_;
        std::shared_ptr<std::uint_fast32_t> sampler_seed_ = std::make_shared<std::uint_fast32_t>(0);
        ompl::base::SpaceInformationPtr si_;
    };
}  // namespace pushplan::detail
