// The gtest main of every test executable (tests/CMakeLists.txt, vkpath_test(); it replaces
// GTest::gtest_main). Built twice: vkpath_test_main for the host-only labels (unit, stats, bench),
// where a skipped test stays a skip, and vkpath_device_test_main (VKPATH_SKIP_FAILS_IN_CI=1) for
// the executables labelled gpu or stress. In CI (environment variable CI=true or CI=1) a test of
// those that skips fails instead, with the reason it gave for skipping: CI must never pass without
// having run the device tests (a missing device is the usual reason, see tests/gpu/gpu_env.h).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>

namespace {

#if VKPATH_SKIP_FAILS_IN_CI
/// True when running in CI (environment variable CI=true or CI=1).
bool inCi() {
    const char* ci = std::getenv("CI");
    return ci && (std::strcmp(ci, "true") == 0 || std::strcmp(ci, "1") == 0);
}

/// Turns a skipped test into a failed one. Appended after gtest's default printer, so its
/// OnTestEnd runs first (gtest calls OnTestEnd in reverse order of registration): the printer then
/// sees a failed test and prints "[  FAILED  ]", never the "[  SKIPPED ]" that CTest's
/// SKIP_REGULAR_EXPRESSION (set by gtest_discover_tests) would report as skipped.
class SkipIsFailureInCi : public ::testing::EmptyTestEventListener {
    void OnTestEnd(const ::testing::TestInfo& info) override {
        const ::testing::TestResult& r = *info.result();
        if (!r.Skipped()) return;
        std::string why;
        for (int i = 0; i < r.total_part_count(); ++i)
            if (r.GetTestPartResult(i).skipped()) why += r.GetTestPartResult(i).message();
        // Still inside the test (gtest clears the current test after OnTestEnd): the failure is its.
        ADD_FAILURE() << "this test skipped, which fails in CI (CI=" << std::getenv("CI")
                      << "): every test of a gpu or stress executable must run there. It skipped because: "
                      << (why.empty() ? "(no reason given)" : why);
    }
};
#endif

}  // namespace

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
#if VKPATH_SKIP_FAILS_IN_CI
    if (inCi()) ::testing::UnitTest::GetInstance()->listeners().Append(new SkipIsFailureInCi);
#endif
    return RUN_ALL_TESTS();
}
