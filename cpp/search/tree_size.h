// What a progress report asks of a search: how many states its tree holds.
#pragma once

#include <cstddef>

namespace pushplan::detail
{
    /// A search that can say how many states its tree holds. Read while the search is
    /// paused (a portfolio's round end, or after solve()).
    class TreeSize
    {
    public:
        virtual ~TreeSize() = default;
        virtual std::size_t treeSize() const = 0;
    };
}  // namespace pushplan::detail
