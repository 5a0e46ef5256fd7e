// Where the parts of one pushplan state lie: within OMPL's memory block (StateLayout), and
// in the flat layout states cross the bridge in (FlatLayout).
#pragma once

#include <cstddef>

namespace pushplan::detail
{
    /// Byte offsets within a state's block: OMPL's headers first, then the numbers —
    /// joint values, every object's x and y, every object's yaw (inside its SO2 state) —
    /// then, in robust planning, the perturbed worlds' object poses (not a component:
    /// OMPL's metric, samplers and projections never see them).
    struct StateLayout
    {
        std::size_t components, joints, objects, object_headers, joint_values, xy_values, yaws, particles, size;
    };

    /// The layout for `dof` joints, `objects` movable objects and `particle_values`
    /// doubles of perturbed worlds.
    StateLayout stateLayout(std::size_t dof, std::size_t objects, std::size_t particle_values);

    /// A state in the bridge's flat layout (Rust's `State::to_flat`): the joint values
    /// (rad or m), then every object's x, y (m) and yaw (rad), world frame. The one place
    /// the C++ side writes that layout out.
    struct FlatLayout
    {
        std::size_t dof, objects;

        /// Values in one state.
        std::size_t size() const { return dof + 3 * objects; }
        /// Where object `o`'s x is; its y and yaw follow.
        std::size_t object(std::size_t o) const { return dof + 3 * o; }
    };
}  // namespace pushplan::detail
