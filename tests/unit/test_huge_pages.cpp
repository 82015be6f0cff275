// host/core/huge_pages.cpp: the GLIBC_TUNABLES value vkpath re-executes itself with. That the
// binary really runs with it (and that glibc.malloc.hugetlb=0 opts out) is CliBench.HugePagesByDefault.
#include <gtest/gtest.h>

#include <cstdlib>

#include "core/huge_pages.h"

namespace vkp {
namespace {

TEST(HugePages, TheTunableIsAppendedOnce) {
    EXPECT_EQ(tunablesWithHugePages(nullptr), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(tunablesWithHugePages(""), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(tunablesWithHugePages("glibc.malloc.arena_max=2"), "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
    // Already named, with any value: nothing to do (=0 is how a user opts out).
    EXPECT_EQ(tunablesWithHugePages("glibc.malloc.hugetlb=1"), std::nullopt);
    EXPECT_EQ(tunablesWithHugePages("glibc.malloc.hugetlb=0"), std::nullopt);
    EXPECT_EQ(tunablesWithHugePages("glibc.malloc.arena_max=2:glibc.malloc.hugetlb=0"), std::nullopt);
    // A longer name that starts with it is another tunable.
    EXPECT_EQ(tunablesWithHugePages("glibc.malloc.hugetlbx=0"), "glibc.malloc.hugetlbx=0:glibc.malloc.hugetlb=1");
}

TEST(HugePages, RequestedOnlyWhenTheLastValueIsOne) {
    const char* saved = std::getenv("GLIBC_TUNABLES");
    const std::string keep = saved ? saved : "";
    auto with = [](const char* v) {
        if (v) setenv("GLIBC_TUNABLES", v, 1);
        else unsetenv("GLIBC_TUNABLES");
        return hugePagesRequested();
    };
    EXPECT_FALSE(with(nullptr));
    EXPECT_FALSE(with("glibc.malloc.arena_max=2"));
    EXPECT_TRUE(with("glibc.malloc.hugetlb=1"));
    EXPECT_TRUE(with("glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1"));
    EXPECT_FALSE(with("glibc.malloc.hugetlb=0"));
    EXPECT_FALSE(with("glibc.malloc.hugetlb=1:glibc.malloc.hugetlb=0"));
    if (saved) setenv("GLIBC_TUNABLES", keep.c_str(), 1);
    else unsetenv("GLIBC_TUNABLES");
}

}  // namespace
}  // namespace vkp
