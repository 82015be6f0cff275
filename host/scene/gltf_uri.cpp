// The external files of a glTF document (gltf_parts.h externalFiles): every buffers[i].uri and
// images[i].uri that is not a data: URI, checked before tinygltf reads anything, each error naming
// the buffer or image and quoting the uri as the file writes it.
#include <cctype>

#include <nlohmann/json.hpp>

#include "scene/file_references.h"
#include "scene/gltf_parts.h"

namespace vkp::gltf {

namespace {

/// The data: URIs tinygltf 2.7 decodes itself (IsDataURI); any other uri is a file to it.
bool tinygltfDataUri(const std::string& uri) {
    static const char* const kHeaders[] = {
        "data:application/octet-stream;base64,", "data:image/jpeg;base64,", "data:image/png;base64,",
        "data:image/bmp;base64,", "data:image/gif;base64,", "data:text/plain;base64,",
        "data:application/gltf-buffer;base64,",
    };
    for (const char* h : kHeaders)
        if (uri.rfind(h, 0) == 0) return true;
    return false;
}

int hexDigit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

/// tinygltf's decoding of a uri (dlib's urldecode: "+" is a space, "%xy" a byte), the path it
/// asks the file callbacks for is its base folder + "/" + this.
std::string tinygltfDecode(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            out += ' ';
        } else if (uri[i] == '%' && uri.size() > i + 2) {
            const int hi = hexDigit(uri[i + 1]), lo = hexDigit(uri[i + 2]);
            out += static_cast<char>(((hi < 0 ? 0 : hi) << 4) | (lo < 0 ? 0 : lo));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

/// The path a uri names (RFC 3986: "%xy" a byte, "+" itself), or a problem in `problem`.
std::string decodePath(const std::string& uri, std::string& problem) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] != '%') {
            out += uri[i];
            continue;
        }
        const int hi = i + 1 < uri.size() ? hexDigit(uri[i + 1]) : -1;
        const int lo = i + 2 < uri.size() ? hexDigit(uri[i + 2]) : -1;
        if (hi < 0 || lo < 0) {
            problem = "invalid percent-encoding \"" + uri.substr(i, 3) + "\" (a % must be followed by two hex digits)";
            return {};
        }
        if (hi == 0 && lo == 0) {
            problem = "contains %00 (a NUL byte cannot be part of a file name)";
            return {};
        }
        out += static_cast<char>(hi << 4 | lo);
        i += 2;
    }
    return out;
}

/// The uri's scheme ("http" of "http://..."), or empty for a relative reference or a path.
std::string scheme(const std::string& uri) {
    if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return {};
    for (std::size_t i = 1; i < uri.size(); ++i) {
        const char c = uri[i];
        if (c == ':') return uri.substr(0, i);
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return {};
    }
    return {};
}

}  // namespace

std::map<std::string, ExternalFile> externalFiles(std::string_view json, const std::string& file,
                                                  const std::filesystem::path& base, const AllowedPaths& allowed) {
    std::map<std::string, ExternalFile> files;
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(json);
    } catch (const std::exception&) {
        return files;  // tinygltf reports invalid JSON
    }
    if (!doc.is_object()) return files;
    for (const char* section : {"buffers", "images"}) {
        const auto list = doc.find(section);
        if (list == doc.end() || !list->is_array()) continue;
        for (std::size_t i = 0; i < list->size(); ++i) {
            const nlohmann::json& item = (*list)[i];
            if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
            const std::string uri = item["uri"].get<std::string>();
            if (tinygltfDataUri(uri)) continue;
            const std::string place = std::string(section[0] == 'b' ? "buffer " : "image ") + std::to_string(i) +
                                      ": uri \"" + uri + "\"";
            const std::string s = scheme(uri);
            if (s == "data") fail(file, place, "a data: URI vkpath cannot read (base64 of application/octet-stream, "
                                               "application/gltf-buffer, image/png or image/jpeg expected)");
            std::string text = uri;
            if (s == "file") {  // file:///path or file://localhost/path
                text = uri.substr(5);
                if (text.rfind("//localhost/", 0) == 0) text = text.substr(11);
                else if (text.rfind("///", 0) == 0) text = text.substr(2);
                else fail(file, place, "a file: URI must be file:///path (no host)");
            } else if (s.size() > 1) {  // one letter ("C:/x", a Windows drive) is a relative path here
                fail(file, place, "a " + s + ": URI: vkpath reads only files (relative paths, file: and data: URIs)");
            }
            std::string problem;
            const std::string path = decodePath(text, problem);
            if (!problem.empty()) fail(file, place, problem);
            if (path.empty()) fail(file, place, "names no file");
            const std::filesystem::path resolved = resolveReference(base, path, allowed, problem);
            if (!problem.empty()) fail(file, place, problem);
            std::string asked = base.string();
            if (asked.empty() || asked.back() != '/') asked += '/';
            asked += tinygltfDecode(uri);
            const auto [at, added] = files.emplace(asked, ExternalFile{resolved, place});
            if (!added && at->second.file != resolved) {
                fail(file, place, "names another file than " + at->second.place +
                                      ", but tinygltf would read the same (\"+\" and \"%20\" are both a space to it)");
            }
        }
    }
    return files;
}

}  // namespace vkp::gltf
