#include "scene/file_references.h"

#include <system_error>

namespace vkp {

namespace fs = std::filesystem;

namespace {

/// p made absolute and canonical as far as it exists (the rest normalised lexically).
fs::path canonicalPath(const fs::path& p) {
    std::error_code ec;
    fs::path abs = fs::absolute(p, ec);
    if (ec) abs = p;
    fs::path c = fs::weakly_canonical(abs, ec);
    return ec ? abs.lexically_normal() : c;
}

/// path is root or below it (both canonical).
bool inside(const fs::path& path, const fs::path& root) {
    const fs::path rel = path.lexically_relative(root);
    return !rel.empty() && *rel.begin() != "..";
}

}  // namespace

fs::path resolveReference(const fs::path& folder, const fs::path& reference, const AllowedPaths& allowed,
                          std::string& problem) {
    const fs::path root = canonicalPath(folder.empty() ? fs::path(".") : folder);
    const fs::path resolved = canonicalPath(reference.is_absolute() ? reference : root / reference);
    if (inside(resolved, root)) return resolved;
    for (const fs::path& dir : allowed)
        if (inside(resolved, canonicalPath(dir))) return resolved;
    problem = "resolves to " + resolved.string() + ", outside " + root.string() +
              " (the referring file's folder; symbolic links are followed): add --allow-path DIR to read it";
    return {};
}

}  // namespace vkp
