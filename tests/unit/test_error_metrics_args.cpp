// Command-line flags of the error and stats outputs: --reference, --error-log, --stats-json.
#include <gtest/gtest.h>

#include "cli/args.h"
#include "core/errors.h"

namespace vkp {
namespace {

std::string errorOf(const std::vector<std::string>& a) {
    try {
        parseArgs(a);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ErrorMetricsArgs, Parsed) {
    const CliArgs a = parseArgs({"render", "s.json", "--reference", "r.exr", "--error-log", "e.csv", "--stats-json", "s.json"});
    EXPECT_EQ(a.reference, "r.exr");
    EXPECT_EQ(a.errorLog, "e.csv");
    EXPECT_EQ(a.statsJson, "s.json");
    const CliArgs b = parseArgs({"render", "s.json"});
    EXPECT_TRUE(b.reference.empty());
    EXPECT_TRUE(b.errorLog.empty());
    EXPECT_TRUE(b.statsJson.empty());
    // --reference alone is fine (the final error is printed and goes into --stats-json).
    EXPECT_EQ(parseArgs({"render", "s.json", "--reference", "r.pfm"}).reference, "r.pfm");
}

TEST(ErrorMetricsArgs, Errors) {
    EXPECT_NE(errorOf({"render", "s.json", "--error-log", "e.csv"}).find("--error-log needs --reference"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--reference"}).find("--reference needs a value"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.json", "--stats-json", ""}).find("--stats-json needs a file name"), std::string::npos);
    EXPECT_NE(errorOf({"info", "s.json", "--stats-json", "x.json"}).find("only valid with 'vkpath render'"),
              std::string::npos);
}

}  // namespace
}  // namespace vkp
