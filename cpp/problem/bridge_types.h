// The C++ twins of Rust types the bridge passes as they are (`#[repr(C)]` in Rust, bound
// with cxx::ExternType in src/bridge.rs). build.rs generates them from the Rust
// declarations (pushplan/twins.h, with the offsets each compiler checks), so the two
// cannot drift apart; PathMetrics is public (pushplan.h) and checked here.
#pragma once

#include "pushplan/pushplan.h"
#include "pushplan/twins.h"

#include <cstddef>

namespace pushplan
{
    // Rust's path::PathMetrics.
    static_assert(offsetof(PathMetrics, objects_moved) == 24 && offsetof(PathMetrics, duration) == 40 &&
                      sizeof(PathMetrics) == 48,
                  "PathMetrics must have the layout of Rust's #[repr(C)] path::PathMetrics");
}  // namespace pushplan
