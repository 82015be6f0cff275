// Running the vkpath binary from tests: exit code, stdout and stderr.
#pragma once
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

namespace vkp::test {

struct ProcessResult {
    int exitCode = -1;
    std::string out, err;
};

/// Runs `program args...` in `cwd` through /bin/sh with `envPrefix` (e.g. "VK_ICD_FILENAMES=/x")
/// before it; every argument is single-quoted.
ProcessResult runProcess(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::filesystem::path& cwd, const std::string& envPrefix = "");

/// A program running in the background (fork + exec, no shell): for tests that signal it while
/// it works. Its stdout and stderr go to files in the scratch folder; stdin is /dev/null.
class BackgroundProcess {
public:
    BackgroundProcess(const std::filesystem::path& program, const std::vector<std::string>& args, const std::filesystem::path& cwd);
    ~BackgroundProcess();  ///< kills the process if it still runs
    BackgroundProcess(const BackgroundProcess&) = delete;
    BackgroundProcess& operator=(const BackgroundProcess&) = delete;
    /// Sends `signo` to it.
    void signal(int signo);
    /// Waits until `ready()` is true, the process has exited, or `seconds` passed; true if ready.
    template <class F>
    bool waitFor(F ready, double seconds);
    /// Waits for the exit (killing it with SIGKILL after `seconds`); exit code (128 + signal if it
    /// was killed by one), stdout and stderr.
    ProcessResult wait(double seconds = 120.0);
    bool running();
    /// Its stderr so far.
    std::string errSoFar() const;

private:
    int pid_ = -1;
    int status_ = 0;
    bool exited_ = false;
    std::filesystem::path out_, err_;
};

template <class F>
bool BackgroundProcess::waitFor(F ready, double seconds) {
    for (int i = 0; i < int(seconds * 100); ++i) {
        if (ready()) return true;
        if (!running()) return ready();
        ::usleep(10000);
    }
    return ready();
}

/// Number of lines in s (a final line without '\n' counts).
int lineCount(const std::string& s);

}  // namespace vkp::test
