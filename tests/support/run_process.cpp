#include "run_process.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "test_paths.h"

namespace vkp::test {

namespace {
std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}
std::string slurp(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}
}  // namespace

ProcessResult runProcess(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::filesystem::path& cwd, const std::string& envPrefix) {
    static int counter = 0;
    const auto dir = scratchDir("process");
    const auto out = dir / ("out-" + std::to_string(::getpid()) + "-" + std::to_string(counter) + ".txt");
    const auto err = dir / ("err-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".txt");
    std::string cmd = "cd " + quote(cwd.string()) + " && " + envPrefix + " " + quote(program.string());
    for (const auto& a : args) {  // appended piecewise: GCC 12's -Wrestrict misfires on " " + string&&
        cmd += ' ';
        cmd += quote(a);
    }
    cmd += " >" + quote(out.string()) + " 2>" + quote(err.string()) + " </dev/null";
    const int status = std::system(cmd.c_str());
    ProcessResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    r.out = slurp(out);
    r.err = slurp(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
}

int lineCount(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    if (!s.empty() && s.back() != '\n') ++n;
    return n;
}

}  // namespace vkp::test
