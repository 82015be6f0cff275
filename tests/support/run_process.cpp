#include "run_process.h"

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
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

BackgroundProcess::BackgroundProcess(const std::filesystem::path& program, const std::vector<std::string>& args,
                                     const std::filesystem::path& cwd) {
    static int counter = 0;
    const auto dir = scratchDir("process");
    const std::string tag = std::to_string(::getpid()) + "-bg" + std::to_string(counter++);
    out_ = dir / ("out-" + tag + ".txt");
    err_ = dir / ("err-" + tag + ".txt");
    std::vector<std::string> argv{program.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    pid_ = ::fork();
    if (pid_ == 0) {
        std::vector<char*> cargv;
        for (std::string& a : argv) cargv.push_back(a.data());
        cargv.push_back(nullptr);
        if (::chdir(cwd.c_str()) != 0) ::_exit(127);
        if (!std::freopen("/dev/null", "r", stdin) || !std::freopen(out_.c_str(), "w", stdout) || !std::freopen(err_.c_str(), "w", stderr))
            ::_exit(127);
        ::execv(cargv[0], cargv.data());
        ::_exit(127);
    }
}

BackgroundProcess::~BackgroundProcess() {
    if (running()) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status_, 0);
    }
    std::filesystem::remove(out_);
    std::filesystem::remove(err_);
}

void BackgroundProcess::signal(int signo) {
    if (!exited_) ::kill(pid_, signo);
}

bool BackgroundProcess::running() {
    if (exited_ || pid_ <= 0) return false;
    if (::waitpid(pid_, &status_, WNOHANG) == pid_) exited_ = true;
    return !exited_;
}

std::string BackgroundProcess::errSoFar() const { return slurp(err_); }

ProcessResult BackgroundProcess::wait(double seconds) {
    for (int i = 0; i < int(seconds * 100) && running(); ++i) ::usleep(10000);
    if (running()) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status_, 0);
        exited_ = true;
    }
    ProcessResult r;
    r.exitCode = WIFEXITED(status_) ? WEXITSTATUS(status_) : 128 + (WIFSIGNALED(status_) ? WTERMSIG(status_) : 0);
    r.out = slurp(out_);
    r.err = slurp(err_);
    return r;
}

int lineCount(const std::string& s) {
    int n = 0;
    for (char c : s) n += c == '\n';
    if (!s.empty() && s.back() != '\n') ++n;
    return n;
}

}  // namespace vkp::test
