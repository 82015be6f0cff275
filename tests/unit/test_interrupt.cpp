// SIGINT and SIGTERM around file writes (core/interrupt.h, core/atomic_file.h): a first signal lets
// the write finish; a second one exits at once and leaves neither a temporary file nor a partial
// destination; several files are written all or none. Each signal test runs in a forked child so
// that the handlers and _exit do not touch the test process.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/atomic_file.h"
#include "core/image_io.h"
#include "core/interrupt.h"
#include "test_paths.h"

namespace vkp {
namespace {
namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
    const fs::path dir = test::scratchDir("interrupt") / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

int filesIn(const fs::path& dir) {
    int n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
    return n;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs `body` in a child process with the handlers installed; returns its exit status (or -1 if
/// it did not exit normally, e.g. killed by the signal).
template <class F>
int inChild(F body) {
    const pid_t pid = fork();
    if (pid == 0) {
        installInterruptHandlers();
        body();
        _exit(0);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Interrupt, ExitCodesAreTheShellConvention) {
    EXPECT_EQ(exitCodeForSignal(SIGINT), 130);
    EXPECT_EQ(exitCodeForSignal(SIGTERM), 143);
}

// The first signal only raises the flag: the write in flight completes and is renamed into place.
TEST(Interrupt, FirstSignalLetsTheWriteFinish) {
    const fs::path dir = freshDir("first");
    const int code = inChild([&] {
        writeFileAtomic(dir / "out.txt", [](std::ostream& out) {
            out << "first half ";
            out.flush();
            raise(SIGTERM);
            out << "second half";
        });
        _exit(interruptSignal() == SIGTERM ? 7 : 8);
    });
    EXPECT_EQ(code, 7);
    EXPECT_EQ(slurp(dir / "out.txt"), "first half second half");
    EXPECT_EQ(filesIn(dir), 1);  // no temporary file
}

// A second signal during a write exits at once (130) and deletes the temporary file; the
// destination keeps its old content. Defect 3 of issue 15: `.NAME.tmp-*` files were left.
TEST(Interrupt, SecondSignalDeletesTheTemporaryFileAndExits) {
    const fs::path dir = freshDir("second");
    std::ofstream(dir / "out.txt") << "old";
    const int code = inChild([&] {
        writeFileAtomic(dir / "out.txt", [](std::ostream& out) {
            out << "new, never complete";
            out.flush();
            raise(SIGINT);
            raise(SIGINT);  // does not return
            out << " unreachable";
        });
        _exit(0);
    });
    EXPECT_EQ(code, 130);
    EXPECT_EQ(slurp(dir / "out.txt"), "old");
    EXPECT_EQ(filesIn(dir), 1) << "a temporary file was left";
}

// Several writes in flight (writeFilesAtomic keeps every temporary until all are written): a
// second signal deletes all of them, and no destination is created.
TEST(Interrupt, SecondSignalDeletesEveryTemporaryOfAGroup) {
    const fs::path dir = freshDir("group");
    const int code = inChild([&] {
        writeFilesAtomic({{dir / "a.txt", [](std::ostream& out) { out << "a"; }},
                          {dir / "b.txt", [](std::ostream& out) { out << "b"; }},
                          {dir / "c.txt", [](std::ostream& out) {
                               out << "c";
                               out.flush();
                               raise(SIGTERM);
                               raise(SIGTERM);
                           }}});
        _exit(0);
    });
    EXPECT_EQ(code, 143);
    EXPECT_EQ(filesIn(dir), 0);
}

// All or none (defect 8 of issue 15): when one file of a group fails, the others are not
// replaced either, and no temporary file is left.
TEST(Interrupt, AGroupOfWritesIsAllOrNone) {
    const fs::path dir = freshDir("all-or-none");
    std::ofstream(dir / "a.txt") << "old a";
    EXPECT_THROW(writeFilesAtomic({{dir / "a.txt", [](std::ostream& out) { out << "new a"; }},
                                   {dir / "b.txt", [](std::ostream&) { throw std::runtime_error("b fails"); }}}),
                 std::runtime_error);
    EXPECT_EQ(slurp(dir / "a.txt"), "old a");
    EXPECT_EQ(filesIn(dir), 1);
    writeFilesAtomic({{dir / "a.txt", [](std::ostream& out) { out << "new a"; }}, {dir / "b.txt", [](std::ostream& out) { out << "b"; }}});
    EXPECT_EQ(slurp(dir / "a.txt"), "new a");
    EXPECT_EQ(slurp(dir / "b.txt"), "b");
    EXPECT_EQ(filesIn(dir), 2);
}

// writeImages: an image that cannot be written to one of its paths (here a PFM of an image the
// format cannot hold is impossible, so: a path in a folder that vanished) replaces none.
TEST(Interrupt, ImagesAreWrittenAllOrNone) {
    const fs::path dir = freshDir("images");
    Image img(2, 2);
    img.rgb.assign(12, 0.5f);
    std::ofstream(dir / "a.pfm") << "old";
    EXPECT_ANY_THROW(writeImages(img, {dir / "a.pfm", dir / "gone" / "b.exr"}, {}));
    EXPECT_EQ(slurp(dir / "a.pfm"), "old");
    EXPECT_EQ(filesIn(dir), 1);
}

}  // namespace
}  // namespace vkp
