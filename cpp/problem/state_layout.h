// Where the parts of one pushplan state lie within its single memory block.
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
}  // namespace pushplan::detail
