// Atomic file replacement: a failed write never truncates or clobbers the destination and never
// leaves a temporary file behind.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>

#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/image.h"
#include "core/image_io.h"
#include "test_paths.h"

namespace vkp {
namespace {
namespace fs = std::filesystem;

/// A fresh, empty directory for one test.
fs::path freshDir(const std::string& name) {
    const fs::path dir = test::scratchDir("image_atomic") / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void spit(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

/// Files in `dir` whose names start with dest's temporary prefix.
int tempFilesFor(const fs::path& dest) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dest.parent_path())) {
        if (e.path().filename().string().rfind(atomicTempPrefix(dest), 0) == 0) ++n;
    }
    return n;
}

int entries(const fs::path& dir) {
    return int(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(AtomicFile, WritesAndReplaces) {
    const fs::path dir = freshDir("replace");
    const fs::path dest = dir / "out.csv";
    writeFileAtomic(dest, [](std::ostream& os) { os << "first\n"; });
    EXPECT_EQ(slurp(dest), "first\n");
    writeFileAtomic(dest, [](std::ostream& os) { os << "second\n"; });
    EXPECT_EQ(slurp(dest), "second\n");
    EXPECT_EQ(entries(dir), 1);
}

TEST(AtomicFile, DestinationUntouchedWhileWriting) {
    const fs::path dir = freshDir("during");
    const fs::path dest = dir / "out.txt";
    spit(dest, "old");
    writeFileAtomic(dest, [&](std::ostream& os) {
        os << std::string(200000, 'x');  // more than the stream buffer: really on disk
        os.flush();
        EXPECT_EQ(slurp(dest), "old");
        EXPECT_EQ(tempFilesFor(dest), 1);  // the temporary file sits beside the destination
    });
    EXPECT_EQ(slurp(dest).size(), 200000u);
    EXPECT_EQ(tempFilesFor(dest), 0);
}

TEST(AtomicFile, ThrowingWriterLeavesDestinationAndNoTempFile) {
    const fs::path dir = freshDir("throwing");
    const fs::path dest = dir / "stats.json";
    spit(dest, "precious");
    EXPECT_THROW(writeFileAtomic(dest,
                                 [](std::ostream& os) {
                                     os << std::string(100000, 'y');
                                     throw std::runtime_error("simulated failure");
                                 }),
                 std::runtime_error);
    EXPECT_EQ(slurp(dest), "precious");
    EXPECT_EQ(tempFilesFor(dest), 0);
    EXPECT_EQ(entries(dir), 1);
}

TEST(AtomicFile, FailedStreamIsAnError) {
    const fs::path dir = freshDir("failbit");
    const fs::path dest = dir / "x.txt";
    spit(dest, "keep");
    EXPECT_THROW(writeFileAtomic(dest, [](std::ostream& os) { os.setstate(std::ios::failbit); }), InputError);
    EXPECT_EQ(slurp(dest), "keep");
    EXPECT_EQ(entries(dir), 1);
}

TEST(AtomicFile, ViaPathCommitsOrCleansUp) {
    const fs::path dir = freshDir("viapath");
    const fs::path dest = dir / "lib.bin";
    writeFileAtomicViaPath(dest, [&](const fs::path& tmp) {
        EXPECT_EQ(tmp.parent_path(), dest.parent_path());
        EXPECT_TRUE(fs::exists(tmp));
        spit(tmp, "from library");
    });
    EXPECT_EQ(slurp(dest), "from library");
    EXPECT_THROW(writeFileAtomicViaPath(dest,
                                        [](const fs::path& tmp) {
                                            spit(tmp, "partial");
                                            throw std::runtime_error("library failed");
                                        }),
                 std::runtime_error);
    EXPECT_EQ(slurp(dest), "from library");
    EXPECT_EQ(entries(dir), 1);
}

TEST(AtomicFile, MissingDirectoryFailsCleanly) {
    const fs::path dir = freshDir("missing");
    const fs::path dest = dir / "nope" / "out.png";
    try {
        writeImage(Image(2, 2), dest);
        FAIL() << "no exception";
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(dest.string() + ": ", 0), 0u) << msg;
        EXPECT_NE(msg.find("does not exist"), std::string::npos) << msg;
    }
    EXPECT_FALSE(fs::exists(dir / "nope"));
    EXPECT_EQ(entries(dir), 0);
}

TEST(AtomicFile, KeepsPermissionsOfReplacedFile) {
    const fs::path dir = freshDir("mode");
    const fs::path dest = dir / "out.pfm";
    spit(dest, "old");
    ASSERT_EQ(::chmod(dest.c_str(), 0640), 0);
    writeImage(Image(1, 1), dest);
    struct stat st {};
    ASSERT_EQ(::stat(dest.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0640u);
}

TEST(AtomicFile, FailingImageEncodeKeepsOldImage) {
    const fs::path dir = freshDir("encode_fail");
    const fs::path dest = dir / "render.exr";
    spit(dest, "previous render");
    Image broken(4, 4);
    broken.rgb.resize(5);  // inconsistent: the encoder throws
    EXPECT_THROW(writeImage(broken, dest), std::invalid_argument);
    EXPECT_EQ(slurp(dest), "previous render");
    EXPECT_EQ(entries(dir), 1);
}

// A directory vkpath may not write to is refused before rendering. Root ignores directory
// permissions (CI runs as root), so as root the check runs in a child that has become `nobody`
// (uid and gid 65534), for whom the directory (root's, mode 0555) is read-only.
TEST(AtomicFile, UnwritableDirectoryIsReportedUpFront) {
    const fs::path dir = freshDir("readonly");
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read | fs::perms::group_exec |
                             fs::perms::others_read | fs::perms::others_exec);
    auto refused = [&]() {
        try {
            checkOutputPath(dir / "out.png");
        } catch (const InputError& e) {
            return std::string(e.what()).find("cannot create a file") != std::string::npos;
        }
        return false;
    };
    bool ok = false;
    if (::geteuid() != 0) {
        ok = refused();
    } else {
        const pid_t child = ::fork();
        ASSERT_GE(child, 0) << "fork failed";
        if (child == 0) {
            if (::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(2);
            ::_exit(refused() ? 0 : 1);
        }
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        ASSERT_TRUE(WIFEXITED(status));
        ASSERT_NE(WEXITSTATUS(status), 2) << "could not become nobody (setuid)";
        ok = WEXITSTATUS(status) == 0;
    }
    fs::permissions(dir, fs::perms::owner_all);
    EXPECT_TRUE(ok) << "checkOutputPath must refuse a directory it cannot write to";
    EXPECT_EQ(entries(dir), 0);
}

TEST(AtomicFile, NonRegularDestinationsAreRejected) {
    const fs::path dir = freshDir("nonregular");
    EXPECT_THROW(checkCanCreateFile(dir), InputError);  // a directory
    EXPECT_THROW(checkCanCreateFile("/dev/null"), InputError);
    EXPECT_THROW(writeFileAtomic(dir / "", [](std::ostream&) {}), InputError);  // no file name
}

}  // namespace
}  // namespace vkp
