// OMPL's benchmark tooling on one scene (declared for the cxx bridge in src/ffi/entry.rs).
#pragma once

#include "rust/cxx.h"

namespace pushplan::bridge
{
    struct BenchOptions;

    /// Runs ompl::tools::Benchmark on a scene with the given planners and writes its log.
    void benchmark_scene(rust::Str scene_path, const BenchOptions &options);
}  // namespace pushplan::bridge
