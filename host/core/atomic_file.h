// Atomic file replacement: write a temporary file beside the destination, fsync it, rename it over
// the destination. Readers see either the old file or the complete new one, never a partial file.
#pragma once
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace vkp {

/// Replaces `dest` with what `write` puts into the stream, atomically. The stream writes to a new
/// temporary file ".<name>.tmp-<pid>-<n>" in dest's directory (same file system, so the final
/// rename is atomic); after `write` returns, the data is flushed and fsync'ed, the file is renamed
/// over `dest` and the directory is fsync'ed. A replaced file keeps its permission bits; a new one
/// gets 0666 & ~umask. On any failure (cannot create, write error, `write` throws or leaves the
/// stream in a failed state) the temporary file is removed, `dest` is left untouched and an
/// exception is thrown: InputError "<dest>: <what failed>: <reason>" for I/O failures, or
/// whatever `write` threw.
void writeFileAtomic(const std::filesystem::path& dest, const std::function<void(std::ostream&)>& write);

/// One file of writeFilesAtomic: its destination and what to write into it.
struct AtomicWrite {
    std::filesystem::path dest;
    std::function<void(std::ostream&)> write;
};

/// Replaces every file of `files`, all or none: each is written to its own temporary file and
/// synced first; only when every one succeeded are they renamed over their destinations, in order.
/// On a failure before the renames every temporary file is removed, every destination untouched,
/// and the error is thrown as by writeFileAtomic. Two entries must not name the same destination.
void writeFilesAtomic(const std::vector<AtomicWrite>& files);

/// The same for libraries that can only write to a path: `write` receives the path of an empty
/// temporary file in dest's directory and must (re)write it completely, throwing on failure. The
/// file is then fsync'ed and renamed over `dest`; on failure it is removed and `dest` untouched.
void writeFileAtomicViaPath(const std::filesystem::path& dest,
                            const std::function<void(const std::filesystem::path& tmp)>& write);

/// Checks, without touching `dest`, that writeFileAtomic(dest, ...) can create its file: dest has
/// a file name, its directory exists, dest is not a directory or other non-regular file, and a file
/// can be created in the directory (a probe temporary file is created and removed). Throws
/// InputError "<dest>: <reason>" otherwise. Use it before long work whose result goes to `dest`.
void checkCanCreateFile(const std::filesystem::path& dest);

/// The name prefix of dest's temporary files: "." + dest.filename() + ".tmp-".
std::string atomicTempPrefix(const std::filesystem::path& dest);

}  // namespace vkp
