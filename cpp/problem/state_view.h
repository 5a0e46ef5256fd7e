// The flat-state view of one problem: OMPL's states and controls of the pushplan state
// space read into and written from the bridge's flat layout (the one place the C++ side
// converts them).
#pragma once

#include "pushplan/cpp/problem/state_layout.h"
#include "pushplan/src/bridge.rs.h"
#include "rust/cxx.h"

#include <ompl/base/State.h>
#include <ompl/control/Control.h>
#include <ompl/control/PathControl.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace pushplan::detail
{
    /// A control path, flat: the controls one after another, their step counts, and the
    /// states at the start and after each control.
    struct FlatPath
    {
        std::vector<double> controls;
        std::vector<std::size_t> steps;
        std::vector<double> states;
    };

    /// How one problem's states lie (fixed once its state space is made): the compound
    /// [joints (RealVector), object 1 (SE2), ...] with the perturbed worlds' poses after
    /// it, converted to and from flat states. Stateless: callers bring their buffers, so
    /// one view serves every OMPL class of the problem.
    class StateView
    {
    public:
        /// The view of `info`'s states carrying `particle_values` doubles of perturbed
        /// worlds; in Static RRT's problem (`static_clutter`) the clutter stays where it
        /// starts.
        StateView(std::shared_ptr<const bridge::SceneInfo> info, std::size_t particle_values, bool static_clutter);

        const bridge::SceneInfo &info() const { return *info_; }
        /// The bridge's flat layout of this scene's states.
        FlatLayout flat() const { return FlatLayout{info_->dof, info_->objects}; }
        std::size_t stateSize() const { return flat().size(); }
        std::size_t controlSize() const { return 3 + info_->dof; }
        /// Where the parts of a state lie in OMPL's block.
        const StateLayout &layout() const { return layout_; }

        /// Flat copy of an OMPL state.
        void read(const ompl::base::State *state, std::vector<double> &out) const;
        /// Writes a flat state into an OMPL state.
        void write(const std::vector<double> &in, ompl::base::State *state) const;
        void readControl(const ompl::control::Control *control, std::vector<double> &out) const;
        FlatPath readPath(const ompl::control::PathControl &path) const;

        /// The perturbed worlds' poses within a state's block (empty without worlds).
        rust::Slice<const double> particles(const ompl::base::State *state) const;
        rust::Slice<double> particles(ompl::base::State *state) const;

        /// In Static RRT's problem, puts every object except the goal object back at its
        /// start pose (a sample of that problem); otherwise leaves `flat` as it is.
        void pinClutter(std::vector<double> &flat) const;

    private:
        std::shared_ptr<const bridge::SceneInfo> info_;
        StateLayout layout_;
        bool static_clutter_;
    };

    inline rust::Slice<const double> slice(const std::vector<double> &v)
    {
        return rust::Slice<const double>(v.data(), v.size());
    }

    inline rust::Slice<const std::size_t> slice(const std::vector<std::size_t> &v)
    {
        return rust::Slice<const std::size_t>(v.data(), v.size());
    }

    inline rust::Slice<const std::int64_t> slice(const std::vector<std::int64_t> &v)
    {
        return rust::Slice<const std::int64_t>(v.data(), v.size());
    }
}  // namespace pushplan::detail
