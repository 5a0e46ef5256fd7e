// The CLI's way into the C++ planner (declared for the cxx bridge in src/ffi/entry.rs).
#pragma once

#include "rust/cxx.h"

namespace pushplan::bridge
{
    struct SolveOptions;
    struct SolveOutput;
    struct SearchProgress;
    struct ReachOptions;
    struct ReachOutput;

    /// Plans a scene file, telling `progress` how far it is (with options.progress);
    /// throws (a Rust Err) on bad input.
    SolveOutput solve(rust::Str scene_path, const SolveOptions &options,
                      rust::Fn<void(const SearchProgress &)> progress);

    /// Reaches a grasp of `object` from the arm at `from_q` with the objects at
    /// `from_objects` (x, y, yaw each); from the scene's start if `from_q` is empty.
    ReachOutput reach(rust::Str scene_path, rust::Str object, rust::Slice<const double> from_q,
                      rust::Slice<const double> from_objects, const ReachOptions &options);
}  // namespace pushplan::bridge
