// The CLI's way into the C++ planner (declared for the cxx bridge in src/ffi/entry.rs).
#pragma once

#include "rust/cxx.h"

namespace pushplan::bridge
{
    struct SolveOptions;
    struct SolveOutput;
    struct SearchProgress;

    /// Plans a scene file, telling `progress` how far it is (with options.progress);
    /// throws (a Rust Err) on bad input.
    SolveOutput solve(rust::Str scene_path, const SolveOptions &options,
                      rust::Fn<void(const SearchProgress &)> progress);
}  // namespace pushplan::bridge
