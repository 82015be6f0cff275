// Every file vkpath reads is a regular file of bounded size (core/input_file.h): a device, a FIFO
// or a symbolic link to one is one error line naming the file, from each loader, never a read that
// does not end. (The vkpath binary on /dev/zero itself: test_cli_errors, under a memory limit.)
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <fstream>
#include <string>

#include "core/errors.h"
#include "core/image_io.h"
#include "core/input_file.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "input_error.h"
#include "test_paths.h"

namespace {

namespace fs = std::filesystem;
using namespace vkp;

using test::inputErrorOf;

struct InputFile : ::testing::Test {
    fs::path dir = test::scratchDir("input_file");
    fs::path write(const std::string& name, const std::string& bytes) {
        std::ofstream(dir / name, std::ios::binary) << bytes;
        return dir / name;
    }
    /// A symbolic link dir/name -> target (replacing an old one).
    fs::path link(const std::string& name, const fs::path& target) {
        fs::remove(dir / name);
        fs::create_symlink(target, dir / name);
        return dir / name;
    }
    /// A FIFO dir/name that no process writes to.
    fs::path fifo(const std::string& name) {
        fs::remove(dir / name);
        EXPECT_EQ(::mkfifo((dir / name).c_str(), 0600), 0);
        return dir / name;
    }
};

TEST_F(InputFile, ReadsARegularFileWholeAndThroughASymbolicLink) {
    const std::string bytes("a\0b\xff\n", 5);
    const fs::path file = write("bytes.bin", bytes);
    EXPECT_EQ(readInputFile(file), bytes);
    EXPECT_EQ(readInputFile(link("bytes-link.bin", file)), bytes);
    const std::vector<unsigned char> u = readInputBytes(file);
    EXPECT_EQ(std::string(u.begin(), u.end()), bytes);
    EXPECT_EQ(readInputFile(write("empty.bin", "")), "");
}

TEST_F(InputFile, RefusesDevicesFifosAndLinksToThemInOneLine) {
    const std::string notRegular = ": cannot read: not a regular file (a device, FIFO or socket)";
    // A limit of 1 MiB, so that a regression reads 1 MiB of /dev/zero, not memory without bound.
    for (const fs::path& p : {fs::path("/dev/null"), fs::path("/dev/zero"), fs::path("/dev/urandom"),
                              link("zero-link.json", "/dev/zero"), link("link-to-link.json", dir / "zero-link.json"),
                              fifo("fifo.json")}) {
        if (!fs::exists(p)) continue;
        EXPECT_EQ(inputErrorOf([&] { readInputFile(p, 1 << 20); }), p.string() + notRegular);
    }
}

TEST_F(InputFile, MissingDirectoryAndTooLarge) {
    fs::remove(dir / "missing.json");
    EXPECT_EQ(inputErrorOf([&] { readInputFile(dir / "missing.json"); }), (dir / "missing.json").string() + ": cannot read: no such file");
    EXPECT_EQ(inputErrorOf([&] { readInputFile(dir); }), dir.string() + ": cannot read: is a directory");
    const fs::path ten = write("ten.bin", "0123456789");
    EXPECT_EQ(readInputFile(ten, 10), "0123456789");
    EXPECT_EQ(inputErrorOf([&] { readInputFile(ten, 9); }), ten.string() + ": cannot read: larger than 9 bytes");
}

// Each loader reads through the helper: a link to a device or a FIFO is refused by name, whatever
// refers to it.
TEST_F(InputFile, EveryLoaderRefusesDevicesAndFifos) {
    const std::string notRegular = "not a regular file";
    const fs::path scene = link("dev.json", "/dev/null");
    EXPECT_EQ(inputErrorOf([&] { loadSceneJson(scene); }), scene.string() + ": cannot read: " + notRegular + " (a device, FIFO or socket)");
    const fs::path gltf = link("dev.gltf", "/dev/null");
    EXPECT_NE(inputErrorOf([&] { loadSceneGltf(gltf); }).find(gltf.string() + ": cannot read: " + notRegular), std::string::npos);
    const fs::path image = link("dev.exr", "/dev/null");
    EXPECT_NE(inputErrorOf([&] { readImage(image); }).find(image.string() + ": cannot read: " + notRegular), std::string::npos);

    // A glTF buffer, an environment map and an included glTF file of a JSON scene: FIFOs beside
    // the file that names them.
    fifo("fifo.bin");
    const fs::path withBuffer = write("buffer.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "fifo.bin", "byteLength": 4}]})");
    const std::string b = inputErrorOf([&] { loadSceneGltf(withBuffer); });
    EXPECT_NE(b.find("buffer.gltf: buffer 0: uri \"fifo.bin\": cannot read"), std::string::npos) << b;
    EXPECT_NE(b.find(notRegular), std::string::npos) << b;
    fifo("fifo.hdr");
    const std::string camera = R"("camera": {"lookfrom": [0,0,1], "lookat": [0,0,0], "vfov": 40, "width": 8, "height": 8})";
    const fs::path env = write("env.json", "{" + camera + R"(, "objects": [], "environment": {"file": "fifo.hdr"}})");
    const std::string e = inputErrorOf([&] { loadSceneJson(env); });
    EXPECT_NE(e.find("env.json: /environment/file:"), std::string::npos) << e;
    EXPECT_NE(e.find(notRegular), std::string::npos) << e;
    fifo("fifo.gltf");
    const fs::path include = write("include.json", "{" + camera + R"(, "objects": [{"type": "gltf", "file": "fifo.gltf"}]})");
    const std::string i = inputErrorOf([&] { loadSceneJson(include); });
    EXPECT_NE(i.find("include.json: /objects/0/file:"), std::string::npos) << i;
    EXPECT_NE(i.find(notRegular), std::string::npos) << i;
}

}  // namespace
