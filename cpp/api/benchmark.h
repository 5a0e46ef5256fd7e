// OMPL's benchmark tooling on one scene (declared for the cxx bridge in src/bridge/entry.rs).
#pragma once

#include "pushplan/cpp/problem/bridge_types.h"
#include "rust/cxx.h"

#include <cstdint>

namespace pushplan::bridge
{
    /// Runs run `run` of ompl::tools::Benchmark (a planner on a scene, seeded from
    /// `settings.seed` and `run` only) and writes its log to `log`.
    void benchmark_scene(rust::Str scene_path, const detail::RunSettings &settings, std::uint32_t run, rust::Str log);
}  // namespace pushplan::bridge
