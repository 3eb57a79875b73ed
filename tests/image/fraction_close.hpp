// The fraction of two equally long sequences' elements that `close` judges close (0 for sequences
// of other lengths, with a failure): the image tests' tolerance, "within d at p % of the pixels".
#pragma once

#include <cstddef>

#include <gtest/gtest.h>

namespace echosim::test {

template <class A, class B, class Close>
double fraction_close(const A& a, const B& b, Close close)
{
    EXPECT_EQ(a.size(), b.size());
    if (a.size() != b.size() || a.empty()) return 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += close(a[i], b[i]);
    return double(n) / double(a.size());
}

}  // namespace echosim::test
