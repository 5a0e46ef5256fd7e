// The C++ test programs' one check: prints "ok: WHAT" or "FAILED: WHAT" and counts the
// failures; tests/integration/cpp_api.rs counts the "ok" lines.
#pragma once

#include <iostream>
#include <string>

namespace test
{
    inline int failures = 0;

    inline void expect(bool ok, const std::string &what)
    {
        std::cout << (ok ? "ok: " : "FAILED: ") << what << "\n";
        if (!ok)
            ++failures;
    }
}  // namespace test
