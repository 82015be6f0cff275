// Which files a scene may make vkpath read: a JSON scene's included glTF files and environment
// map, a glTF file's buffers and images. A reference must resolve, with symbolic links followed, to
// a path inside the referring file's folder (or below it) or inside a folder the command line
// allows (--allow-path DIR, repeatable), so that a file from elsewhere cannot make vkpath read
// /etc/hostname, ~/.ssh/... or a device through "../../..", an absolute path or a link.
// docs/design.md "Files a scene may read".
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace vkp {

/// The folders besides the referring file's own that its references may reach (--allow-path).
using AllowedPaths = std::vector<std::filesystem::path>;

/// The path `reference` names, resolved against `folder` (the referring file's folder) when
/// relative and made canonical with std::filesystem::weakly_canonical (symbolic links followed, as
/// far as the path exists). Returns it when it lies in folder, in one of `allowed` (each made
/// canonical too) or below one of them; otherwise sets `problem` to one clause saying where it
/// resolves and how to allow it, and returns an empty path.
std::filesystem::path resolveReference(const std::filesystem::path& folder, const std::filesystem::path& reference,
                                       const AllowedPaths& allowed, std::string& problem);

}  // namespace vkp
