#include "core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <memory>
#include <ostream>
#include <streambuf>
#include <system_error>

#include "core/errors.h"
#include "core/interrupt.h"

namespace vkp {
namespace fs = std::filesystem;

namespace {

std::atomic<uint64_t> g_tempCounter{0};

std::string errnoText(int e) { return std::error_code(e, std::generic_category()).message(); }

[[noreturn]] void fail(const fs::path& dest, const std::string& what, int err) {
    throw InputError(dest.string() + ": " + what + (err ? ": " + errnoText(err) : std::string()));
}

fs::path directoryOf(const fs::path& dest) {
    fs::path dir = dest.parent_path();
    return dir.empty() ? fs::path(".") : dir;
}

/// Rejects destinations that cannot be replaced by a regular file. Returns the mode of an existing
/// regular destination (to copy onto the replacement), or -1 when there is none.
int checkDestination(const fs::path& dest) {
    if (dest.filename().empty() || dest.filename() == "." || dest.filename() == "..") {
        fail(dest, "not a file name", 0);
    }
    const fs::path dir = directoryOf(dest);
    std::error_code ec;
    const fs::file_status dirStatus = fs::status(dir, ec);
    if (!fs::exists(dirStatus)) fail(dest, "directory '" + dir.string() + "' does not exist", 0);
    if (!fs::is_directory(dirStatus)) fail(dest, "'" + dir.string() + "' is not a directory", 0);
    struct stat st {};
    if (::stat(dest.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) fail(dest, "is a directory", 0);
        if (!S_ISREG(st.st_mode)) fail(dest, "exists and is not a regular file", 0);
        return int(st.st_mode & 07777);
    }
    return -1;
}

/// An open temporary file that is removed unless committed.
struct TempFile {
    fs::path path;
    int fd = -1;
    bool committed = false;
    std::unique_ptr<TempFileGuard> guard;  ///< a second SIGINT/SIGTERM deletes the file (core/interrupt.h)

    TempFile() = default;
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    ~TempFile() {
        if (fd >= 0) ::close(fd);
        if (!committed && !path.empty()) ::unlink(path.c_str());
    }
};

void createTemp(const fs::path& dest, TempFile& tmp) {
    const int destMode = checkDestination(dest);
    const fs::path dir = directoryOf(dest);
    const std::string prefix = atomicTempPrefix(dest) + std::to_string(::getpid()) + "-";
    for (int attempt = 0;; ++attempt) {
        fs::path candidate = dir / (prefix + std::to_string(g_tempCounter.fetch_add(1)));
        auto guard = std::make_unique<TempFileGuard>(candidate.c_str());  // before the file exists
        const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            tmp.path = std::move(candidate);
            tmp.fd = fd;
            tmp.guard = std::move(guard);
            break;
        }
        const int err = errno;
        if ((err != EEXIST && err != EINTR) || attempt >= 100) {
            fail(dest, "cannot create a file in '" + dir.string() + "'", err);
        }
    }
    if (destMode >= 0) (void)::fchmod(tmp.fd, mode_t(destMode));  // best effort: keep permissions
}

/// fsync + close the temporary file (commit's first half).
void syncAndClose(const fs::path& dest, TempFile& tmp) {
    if (::fsync(tmp.fd) != 0) {
        const int err = errno;
        fail(dest, "cannot sync '" + tmp.path.string() + "'", err);
    }
    const int fd = tmp.fd;
    tmp.fd = -1;
    if (::close(fd) != 0) {
        const int err = errno;
        fail(dest, "cannot close '" + tmp.path.string() + "'", err);
    }
}

/// Renames the synced temporary file over dest, fsyncs the directory (best effort).
void renameOver(const fs::path& dest, TempFile& tmp) {
    if (::rename(tmp.path.c_str(), dest.c_str()) != 0) {
        const int err = errno;
        fail(dest, "cannot rename '" + tmp.path.string() + "' to it", err);
    }
    tmp.committed = true;
    tmp.guard.reset();
    const int dirFd = ::open(directoryOf(dest).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dirFd >= 0) {
        (void)::fsync(dirFd);  // makes the rename durable; some file systems refuse, that is fine
        ::close(dirFd);
    }
}

/// fsync + close the temporary file, rename it over dest, fsync the directory (best effort).
void commit(const fs::path& dest, TempFile& tmp) {
    syncAndClose(dest, tmp);
    renameOver(dest, tmp);
}


/// An output stream buffer writing to a file descriptor, remembering the first write error.
class FdStreamBuf : public std::streambuf {
public:
    explicit FdStreamBuf(int fd) : fd_(fd) { setp(buf_, buf_ + sizeof(buf_)); }
    int error() const { return err_; }

protected:
    int_type overflow(int_type ch) override {
        if (!flushBuffer()) return traits_type::eof();
        if (!traits_type::eq_int_type(ch, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(ch);
            pbump(1);
        }
        return traits_type::not_eof(ch);
    }
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        if (n < std::streamsize(sizeof(buf_))) return std::streambuf::xsputn(s, n);
        if (!flushBuffer() || !writeAll(s, size_t(n))) return 0;  // large block: bypass the buffer
        return n;
    }
    int sync() override { return flushBuffer() ? 0 : -1; }

private:
    bool flushBuffer() {
        const size_t n = size_t(pptr() - pbase());
        if (n > 0 && !writeAll(pbase(), n)) return false;
        setp(buf_, buf_ + sizeof(buf_));
        return true;
    }
    bool writeAll(const char* p, size_t n) {
        while (n > 0 && err_ == 0) {
            const ssize_t w = ::write(fd_, p, n);
            if (w < 0) {
                if (errno != EINTR) err_ = errno;
                continue;
            }
            p += w;
            n -= size_t(w);
        }
        return err_ == 0;
    }

    int fd_;
    int err_ = 0;
    char buf_[1 << 16];
};

}  // namespace

std::string atomicTempPrefix(const fs::path& dest) {
    std::string prefix = ".";  // appended piecewise: GCC 12's -Wrestrict misfires on "." + string&&
    prefix += dest.filename().string();
    prefix += ".tmp-";
    return prefix;
}

namespace {
void writeInto(const fs::path& dest, TempFile& tmp, const std::function<void(std::ostream&)>& write) {
    FdStreamBuf buf(tmp.fd);
    std::ostream os(&buf);
    write(os);
    os.flush();
    if (buf.error() != 0) fail(dest, "cannot write '" + tmp.path.string() + "'", buf.error());
    if (!os) fail(dest, "writing '" + tmp.path.string() + "' failed", 0);
}
}  // namespace

void writeFileAtomic(const fs::path& dest, const std::function<void(std::ostream&)>& write) {
    TempFile tmp;
    createTemp(dest, tmp);
    writeInto(dest, tmp, write);
    commit(dest, tmp);
}

void writeFilesAtomic(const std::vector<AtomicWrite>& files) {
    std::vector<std::unique_ptr<TempFile>> tmps;  // removed by their destructors unless renamed
    for (const AtomicWrite& f : files) {
        tmps.push_back(std::make_unique<TempFile>());
        createTemp(f.dest, *tmps.back());
        writeInto(f.dest, *tmps.back(), f.write);
        syncAndClose(f.dest, *tmps.back());
    }
    for (std::size_t i = 0; i < files.size(); ++i) renameOver(files[i].dest, *tmps[i]);
}

void writeFileAtomicViaPath(const fs::path& dest, const std::function<void(const fs::path&)>& write) {
    TempFile tmp;
    createTemp(dest, tmp);
    ::close(tmp.fd);  // the callback opens the path itself; reopened below for fsync
    tmp.fd = -1;
    write(tmp.path);
    tmp.fd = ::open(tmp.path.c_str(), O_WRONLY | O_CLOEXEC);
    if (tmp.fd < 0) {
        const int err = errno;
        fail(dest, "cannot reopen '" + tmp.path.string() + "'", err);
    }
    commit(dest, tmp);
}

void checkCanCreateFile(const fs::path& dest) {
    TempFile probe;
    createTemp(dest, probe);  // removed by ~TempFile
}

}  // namespace vkp
