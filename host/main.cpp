// vkpath: entry point. Parses the command line, runs the command, and turns every error into one
// line on stderr and the documented exit code (README "Exit codes").
#include <chrono>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>


#include "cli/args.h"
#include "cli/commands.h"
#include "core/errors.h"
#include "core/huge_pages.h"

int main(int argc, char** argv) {
    vkp::reexecWithHugePages(argv);  // once, first: glibc.malloc.hugetlb=1 (core/huge_pages.h)
    const auto start = std::chrono::steady_clock::now();
    using namespace vkp;
    auto fail = [](int code, const std::string& msg) {
        std::fprintf(stderr, "vkpath: error: %s\n", msg.c_str());
        return code;
    };
    try {
        const CliArgs args = parseArgs(std::vector<std::string>(argv + 1, argv + argc));
        switch (args.command) {
            case Command::Help: std::fputs(usageText(), stdout); return kExitOk;
            case Command::Version: std::printf("vkpath %s\n", VKPATH_VERSION); return kExitOk;
            case Command::Render: return runRender(args, start);
            case Command::Info: return runInfo(args);
            case Command::Devices: return runDevices(args);
            case Command::Merge: return runMerge(args);
        }
    } catch (const InputError& e) {
        return fail(kExitBadInput, e.what());
    } catch (const DeviceError& e) {
        return fail(kExitNoDevice, e.what());
    } catch (const VulkanError& e) {
        return fail(kExitVulkan, e.what());
    } catch (const std::bad_alloc&) {
        return fail(kExitVulkan, "out of host memory");
    } catch (const std::exception& e) {
        // vk::SystemError and anything else at run time
        return fail(kExitVulkan, std::string("Vulkan or runtime failure: ") + e.what());
    }
    return kExitOk;
}
