// The z-test budget of one test executable (statistics: test_gpu_analytic_common.h, file comment).
// An executable declares, with a ZBudgetEnvironment, that it performs at most B z-tests at
// family-wise false-failure probability alpha; each z-test then runs at the Sidak level
// 1 - (1 - alpha)^(1/B), so that the probability that any of them fails for correct code is
// <= alpha, however many processes the tests are spread over.
//
// CTest runs every test case in a process of its own (gtest_discover_tests), so no single process
// sees all of an executable's z-tests. At exit each process therefore records, for every test it
// ran that passed, how many z-tests the test used: a file per test under
// scratchDir("z-budget/<executable>") (test_paths.h), rewritten whenever the test passes again (a
// failed or skipped test may have stopped early: it keeps its record). It then adds up the records
// of all the executable's tests, those of earlier processes included, and fails if the sum exceeds
// B. Once every test has passed once (a whole ctest run, in any order, or the executable run
// alone) the sum is the executable's whole count.
#pragma once
#include <gtest/gtest.h>

#include <map>
#include <string>

namespace vkp::test {

/// z with P(|Z| > z) = alpha for a standard normal Z (bisection on erfc; alpha in (0, 1)).
double normalTwoSidedZ(double alpha);

/// The z-test budget of this executable (see the file comment). One instance: zBudget().
class ZBudget {
public:
    /// Declares at most `tests` z-tests at family-wise false-failure probability `familyAlpha`.
    void declare(int tests, double familyAlpha);
    /// The critical |z| of one test; counts it against the running test.
    double take();
    double z() const { return z_; }
    int used() const { return used_; }  ///< z-tests taken in this process
    int budget() const { return budget_; }
    double alpha() const { return alpha_; }
    /// z-tests taken by each test of this process, by full name (Suite.Name).
    const std::map<std::string, int>& perTest() const { return perTest_; }
    double maxAbsZ = 0.0;  ///< largest |z| seen (reported)

private:
    int budget_ = 1, used_ = 0;
    double alpha_ = 0.01, z_ = 5.0;
    std::map<std::string, int> perTest_;
};
ZBudget& zBudget();

/// gtest environment that declares the budget before the tests and, after them, records what
/// each test used and checks the executable's total against the budget (file comment).
class ZBudgetEnvironment : public ::testing::Environment {
public:
    ZBudgetEnvironment(int tests, double familyAlpha) : tests_(tests), alpha_(familyAlpha) {}
    void SetUp() override;
    void TearDown() override;

private:
    int tests_;
    double alpha_;
};

}  // namespace vkp::test
