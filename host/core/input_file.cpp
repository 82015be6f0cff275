#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "core/errors.h"

namespace vkp {

namespace {

/// Closes a file descriptor when it goes out of scope.
struct Fd {
    int fd = -1;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& reason) {
    throw InputError(path.string() + ": cannot read: " + reason);
}

std::string errnoReason(int err) {
    switch (err) {
        case ENOENT: return "no such file";
        case ENOTDIR: return "no such file (a part of the path is not a folder)";
        case EACCES:
        case EPERM: return "permission denied";
        case ELOOP: return "too many levels of symbolic links";
        default: return std::error_code(err, std::generic_category()).message();
    }
}

/// Reads the file into out (a std::string or a std::vector<unsigned char>).
template <class Bytes>
void readInto(const std::filesystem::path& path, std::uint64_t maxBytes, Bytes& out) {
    // O_NONBLOCK: opening a FIFO without a writer would otherwise wait forever; it does nothing
    // for the regular files that pass the check below.
    Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK)};
    if (f.fd < 0) refuse(path, errnoReason(errno));
    struct stat st {};
    if (::fstat(f.fd, &st) != 0) refuse(path, errnoReason(errno));
    if (S_ISDIR(st.st_mode)) refuse(path, "is a directory");
    if (!S_ISREG(st.st_mode)) refuse(path, "not a regular file (a device, FIFO or socket)");
    const std::string tooLarge = "larger than " + std::to_string(maxBytes) + " bytes";
    if (st.st_size < 0 || static_cast<std::uint64_t>(st.st_size) > maxBytes) refuse(path, tooLarge);
    out.clear();
    constexpr std::size_t kChunk = 1 << 16;
    out.reserve(static_cast<std::size_t>(st.st_size) + kChunk);  // the last read, which finds the end
    for (;;) {
        const std::size_t have = out.size();
        const std::uint64_t room = maxBytes - have;  // one byte more than allowed tells "too large"
        const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(kChunk, room + 1));
        out.resize(have + want);
        const ssize_t got = ::read(f.fd, reinterpret_cast<char*>(out.data()) + have, want);
        if (got < 0) {
            if (errno == EINTR) {
                out.resize(have);
                continue;
            }
            refuse(path, "read error: " + errnoReason(errno));
        }
        out.resize(have + static_cast<std::size_t>(got));
        if (got == 0) break;
        if (out.size() > maxBytes) refuse(path, tooLarge);
    }
}

}  // namespace

std::string readInputFile(const std::filesystem::path& path, std::uint64_t maxBytes) {
    std::string out;
    readInto(path, maxBytes, out);
    return out;
}

std::vector<unsigned char> readInputBytes(const std::filesystem::path& path, std::uint64_t maxBytes) {
    std::vector<unsigned char> out;
    readInto(path, maxBytes, out);
    return out;
}

}  // namespace vkp
