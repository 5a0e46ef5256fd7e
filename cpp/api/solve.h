// The applications' way into the C++ planner (declared for the cxx bridge in
// src/bridge/entry.rs).
#pragma once

#include "pushplan/cpp/problem/bridge_types.h"
#include "rust/cxx.h"

namespace pushplan::bridge
{
    struct SolveOutput;
    struct ReachOutput;
    struct Problem;

    /// Searches `problem`'s scene (loaded, its start set) as `settings` say, every model
    /// a copy of it (`Problem::duplicate`: the scene is not read again), telling
    /// `progress` how far it is (a note: an event) when `report` is set; the path comes
    /// back as found (not shortcut). Throws (a Rust Err) on bad input.
    SolveOutput solve(const Problem &problem, const detail::RunSettings &settings, bool report,
                      rust::Fn<void(const detail::SearchProgress &, rust::Str)> progress);

    /// Reaches a grasp of `object` in `problem`'s scene (a copy of it: not read again) from
    /// the flat state `from` (the scene's start if empty).
    ReachOutput reach(const Problem &problem, rust::Str object, rust::Slice<const double> from,
                      const detail::ReachSettings &settings);
}  // namespace pushplan::bridge
