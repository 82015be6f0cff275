// Reading an input file whole (a scene, a glTF file and its buffers and images, an environment map,
// a reference image): only a regular file, after following symbolic links, and at most a size
// limit. A device (/dev/zero, /dev/urandom), a FIFO or a socket is one error line instead of a read
// that never ends or a memory use that has no bound. Every file vkpath reads goes through here.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace vkp {

/// Largest input file vkpath reads, in bytes: 4 GiB - 1 (a GLB's length field is 32 bits).
inline constexpr std::uint64_t kMaxInputFileBytes = (1ull << 32) - 1;

/// The bytes of `path`, read whole. Symbolic links are followed; the file they reach must be a
/// regular file of at most maxBytes bytes (checked before reading and again while reading, for
/// files whose size grows or is not reported, as in /proc). The file is checked on the opened
/// descriptor, so it cannot be swapped between the check and the read. Throws InputError
/// "<path>: cannot read: <reason>", reason one of "no such file", "is a directory", "not a regular
/// file (a device, FIFO or socket)", "larger than <maxBytes> bytes", "permission denied", or the
/// system's message.
std::string readInputFile(const std::filesystem::path& path, std::uint64_t maxBytes = kMaxInputFileBytes);

/// The same bytes as unsigned chars (image decoders, tinygltf's buffers).
std::vector<unsigned char> readInputBytes(const std::filesystem::path& path,
                                          std::uint64_t maxBytes = kMaxInputFileBytes);

}  // namespace vkp
