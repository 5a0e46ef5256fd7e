// The action space (Sec. III-C): end-effector planar velocities with a null-space sample.
#pragma once

#include "pushplan/cpp/problem/model_handle.h"

#include <ompl/control/ControlSampler.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

namespace pushplan::detail
{
    /// Controls (vx, vy, omega_z, z_1 .. z_n): bounds from the scene's planner section.
    std::shared_ptr<ompl::control::RealVectorControlSpace> makeControlSpace(const ompl::base::StateSpacePtr &space,
                                                                           const bridge::SceneInfo &info);

    /// Samples actions uniformly within the bounds, each with its own null-space sample.
    class EeControlSampler : public ompl::control::ControlSampler
    {
    public:
        EeControlSampler(const ompl::control::ControlSpace *space, std::uint_fast32_t seed);
        void sample(ompl::control::Control *control) override;
        void sample(ompl::control::Control *control, const ompl::base::State *state) override;
        void sampleNext(ompl::control::Control *control, const ompl::control::Control *previous) override;
        void sampleNext(ompl::control::Control *control, const ompl::control::Control *previous,
                        const ompl::base::State *state) override;
    };

    /// How PushControlSampler mixes its controls (probabilities). Measured on the 35
    /// benchmark scenes (BENCHMARKS.md, "Push KPIECE").
    struct PushMix
    {
        /// A control follows a push heading; the rest are uniform (exploration).
        double guided = 0.9;
        /// A guided control pushes an object in the goal object's way out of it, if any is.
        double clear = 0.3;
        /// Otherwise the goal object goes toward a point of the goal disc; the rest toward
        /// a point anywhere on the table (detours round what blocks the straight way).
        double to_goal = 0.5;
    };

    /// Samples as EeControlSampler, except that most end-effector velocities follow the
    /// model's push heading at the state (PushMix; a uniform speed between half and all of
    /// the maximum); the turn rate and null-space sample stay uniform. Scenes without an
    /// object goal get uniform controls only.
    class PushControlSampler : public EeControlSampler
    {
    public:
        /// Steers by the push headings of `model`'s problem (a projection of its own).
        PushControlSampler(const ompl::control::ControlSpace *space, std::uint_fast32_t seed, const ModelHandle &model,
                           PushMix mix);
        void sample(ompl::control::Control *control, const ompl::base::State *state) override;
        void sampleNext(ompl::control::Control *control, const ompl::control::Control *previous,
                        const ompl::base::State *state) override;

    private:
        std::shared_ptr<const StateView> view_;
        rust::Box<bridge::Projection> projection_;
        PushMix mix_;
        std::vector<double> buffer_;
    };
}  // namespace pushplan::detail
