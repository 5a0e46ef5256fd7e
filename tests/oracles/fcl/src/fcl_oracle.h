// FCL as the independent oracle for pushplan's collision queries (tests only).
#pragma once

#include "rust/cxx.h"

namespace pushplan::oracle
{
    struct FclShape;
    struct FclResult;

    /// Collision verdict, separation distance and penetration depth of two shapes by FCL.
    FclResult fcl_query(const FclShape &a, const FclShape &b);
}  // namespace pushplan::oracle
