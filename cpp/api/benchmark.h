// OMPL's benchmark tooling on one scene (declared for the cxx bridge in src/ffi/entry.rs).
#pragma once

#include "rust/cxx.h"

namespace pushplan::bridge
{
    struct BenchOptions;

    /// Runs one run of ompl::tools::Benchmark (a planner on a scene) and writes its log.
    void benchmark_scene(rust::Str scene_path, const BenchOptions &options);
}  // namespace pushplan::bridge
