#include "z_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <unistd.h>

#include "test_paths.h"

namespace vkp::test {
namespace fs = std::filesystem;

double normalTwoSidedZ(double alpha) {
    double lo = 0.0, hi = 40.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (std::erfc(mid / std::sqrt(2.0)) > alpha) lo = mid; else hi = mid;
    }
    return 0.5 * (lo + hi);
}

void ZBudget::declare(int tests, double familyAlpha) {
    budget_ = tests;
    alpha_ = familyAlpha;
    z_ = normalTwoSidedZ(1.0 - std::pow(1.0 - familyAlpha, 1.0 / tests));
}

namespace {
std::string fullName(const ::testing::TestInfo& t) { return std::string(t.test_suite_name()) + "." + t.name(); }
const char* const kOutsideTests = "(outside any test)";
}  // namespace

double ZBudget::take() {
    ++used_;
    const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
    ++perTest_[t ? fullName(*t) : std::string(kOutsideTests)];
    return z_;
}

ZBudget& zBudget() {
    static ZBudget b;
    return b;
}

void ZBudgetEnvironment::SetUp() {
    zBudget().declare(tests_, alpha_);
    std::printf("z-test budget: %d tests, family-wise alpha %.3g, critical |z| %.3f\n", tests_, alpha_, zBudget().z());
}

namespace {

/// The record of test `name`: a file name without '/' (parameterised tests have them).
fs::path recordOf(const fs::path& dir, std::string name) {
    std::replace(name.begin(), name.end(), '/', '_');
    return dir / name;
}

/// Writes `count` to `file` through a temporary beside it, so that a process reading it (ctest -j)
/// sees the old record or the new one, never a partial one.
void writeRecord(const fs::path& file, int count) {
    const fs::path tmp = file.string() + ".tmp" + std::to_string(::getpid());
    std::ofstream(tmp) << count << "\n";
    std::error_code ec;
    fs::rename(tmp, file, ec);
    EXPECT_FALSE(ec) << "cannot write the z-test record " << file << ": " << ec.message();
}

}  // namespace

void ZBudgetEnvironment::TearDown() {
    const ZBudget& b = zBudget();
    std::error_code ec;
    const std::string exe = fs::read_symlink("/proc/self/exe", ec).filename().string();
    ASSERT_FALSE(ec || exe.empty()) << "cannot name this executable: " << ec.message();
    const fs::path dir = scratchDir("z-budget/" + exe);
    const ::testing::UnitTest& u = *::testing::UnitTest::GetInstance();
    int total = 0, recorded = 0, tests = 0;
    for (int i = 0; i < u.total_test_suite_count(); ++i) {
        const ::testing::TestSuite& s = *u.GetTestSuite(i);
        for (int j = 0; j < s.total_test_count(); ++j) {
            const ::testing::TestInfo& t = *s.GetTestInfo(j);
            const fs::path file = recordOf(dir, fullName(t));
            // Only a test that passed ran all its z-tests; a failed or skipped one keeps its record.
            if (t.should_run() && t.result()->Passed()) {
                const auto it = b.perTest().find(fullName(t));
                writeRecord(file, it == b.perTest().end() ? 0 : it->second);
            }
            ++tests;
            int count = 0;
            if (std::ifstream in(file); in >> count) {
                total += count;
                ++recorded;
            }
        }
    }
    if (const auto it = b.perTest().find(kOutsideTests); it != b.perTest().end()) total += it->second;
    std::printf("z-tests used: %d in this process (largest |z| %.2f); %d by the %d of this executable's %d tests "
                "recorded so far, of a budget of %d\n",
                b.used(), b.maxAbsZ, total, recorded, tests, b.budget());
    EXPECT_LE(total, b.budget()) << "the tests of " << exe << " use more z-tests than it declares: raise its budget (records in "
                                 << dir << ")";
}

}  // namespace vkp::test
