#include "render/accum_file.h"

#include <tinyexr.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <ostream>

#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/exr_guards.h"
#include "core/input_file.h"

namespace vkp {

namespace {
constexpr const char* kFormat = "accumulation 1";
constexpr const char* kKeyPrefix = "vkpath.key.";

/// A channel: its name and where its value of pixel i is in the state's arrays.
struct ChannelMap {
    std::string name;
    std::vector<float> RenderState::*array;  // null: the active mask
    std::uint32_t offset;       // float within the pixel's floats
    std::uint32_t stride = kStateFloatsPerPixel;  // floats per pixel of the array
};

std::vector<ChannelMap> channelMaps(bool adaptive, bool aov) {
    std::vector<ChannelMap> m;
    const char* rgb[3] = {"R", "G", "B"};
    for (std::uint32_t c = 0; c < 3; ++c) {
        m.push_back({std::string("sum.") + rgb[c], &RenderState::sum, c});
        m.push_back({std::string("sum_lo.") + rgb[c], &RenderState::sum, 4 + c});
        m.push_back({std::string("sumsq.") + rgb[c], &RenderState::sumSq, c});
        m.push_back({std::string("sumsq_lo.") + rgb[c], &RenderState::sumSq, 4 + c});
    }
    m.push_back({"count", &RenderState::sum, 3});
    m.push_back({"count_lo", &RenderState::sum, 7});
    if (adaptive) {
        for (std::uint32_t c = 0; c < 3; ++c) {
            m.push_back({std::string("decision.") + rgb[c], &RenderState::decision, c});
            m.push_back({std::string("decision_sq.") + rgb[c], &RenderState::decision, 4 + c});
        }
        m.push_back({"decision.count", &RenderState::decision, 3});
        m.push_back({"active", nullptr, 0});
    }
    if (aov) {  // shared/aov.h's sums
        const char* xyz[3] = {"X", "Y", "Z"};
        for (std::uint32_t c = 0; c < 3; ++c) {
            m.push_back({std::string("aov_albedo.") + rgb[c], &RenderState::aov, c, kAovFloatsPerPixel});
            m.push_back({std::string("aov_normal.") + xyz[c], &RenderState::aov, 4 + c, kAovFloatsPerPixel});
            m.push_back({std::string("aov_position.") + xyz[c], &RenderState::aov, 8 + c, kAovFloatsPerPixel});
            m.push_back({std::string("aov_emission.") + rgb[c], &RenderState::aov, 12 + c, kAovFloatsPerPixel});
        }
        m.push_back({"aov_samples", &RenderState::aov, 3, kAovFloatsPerPixel});
        m.push_back({"aov_hits", &RenderState::aov, 7, kAovFloatsPerPixel});
        m.push_back({"aov_indirect.mean", &RenderState::aov, 11, kAovFloatsPerPixel});
        m.push_back({"aov_indirect.sq", &RenderState::aov, 15, kAovFloatsPerPixel});
    }
    std::sort(m.begin(), m.end(), [](const ChannelMap& a, const ChannelMap& b) { return a.name < b.name; });  // EXR's order
    return m;
}

std::string keyAttributeName(const std::string& entry) {
    std::string n = kKeyPrefix + entry;
    std::replace(n.begin(), n.end(), ' ', '_');
    return n;
}

using exr::ExrError;
using exr::HeaderGuard;
using exr::ImageGuard;

std::uint64_t parseU64(const std::filesystem::path& path, const std::string& attr, const std::string& v) {
    std::uint64_t x = 0;
    auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
    if (v.empty() || ec != std::errc() || p != v.data() + v.size())
        throw InputError(path.string() + ": attribute " + attr + " is not a whole number: '" + v + "'");
    return x;
}
/// RenderState::aovFrame as 9 numbers (world origin, eye, view axis), each exact ("%.17g").
std::string formatAovFrame(const AovFrame& f) {
    const double v[9] = {f.worldOrigin.x, f.worldOrigin.y, f.worldOrigin.z, f.eye.x, f.eye.y, f.eye.z, f.viewAxis.x, f.viewAxis.y, f.viewAxis.z};
    std::string s;
    char buf[32];
    for (double x : v) {
        std::snprintf(buf, sizeof buf, "%.17g", x);
        if (!s.empty()) s += ' ';
        s += buf;
    }
    return s;
}

/// The inverse of formatAovFrame; nullopt unless the text is 9 finite numbers.
std::optional<AovFrame> parseAovFrame(const std::string& text) {
    double v[9];
    const char* p = text.c_str();
    for (double& x : v) {
        char* end = nullptr;
        x = std::strtod(p, &end);
        if (end == p || !std::isfinite(x)) return std::nullopt;
        p = end;
    }
    while (*p == ' ') ++p;
    if (*p) return std::nullopt;
    AovFrame f;
    f.worldOrigin = glm::dvec3(v[0], v[1], v[2]);
    f.eye = glm::vec3(float(v[3]), float(v[4]), float(v[5]));
    f.viewAxis = glm::vec3(float(v[6]), float(v[7]), float(v[8]));
    return f;
}

}  // namespace

void encodeAccumFile(std::ostream& out, const std::filesystem::path& path, const RenderKey& key, const RenderState& state) {
    const bool adaptive = state.adaptive();
    const std::vector<ChannelMap> maps = channelMaps(adaptive, !state.aov.empty());
    const std::size_t n = std::size_t(state.pixels());
    std::vector<std::vector<float>> planes(maps.size(), std::vector<float>(n));
    for (std::size_t k = 0; k < maps.size(); ++k)
        for (std::size_t i = 0; i < n; ++i)
            planes[k][i] = maps[k].array ? (state.*maps[k].array)[i * maps[k].stride + maps[k].offset] : float(state.active[i]);

    std::vector<EXRChannelInfo> channels(maps.size());
    std::vector<int> types(maps.size(), TINYEXR_PIXELTYPE_FLOAT);
    std::vector<unsigned char*> ptrs(maps.size());
    for (std::size_t k = 0; k < maps.size(); ++k) {
        std::memset(&channels[k], 0, sizeof(EXRChannelInfo));
        std::strncpy(channels[k].name, maps[k].name.c_str(), sizeof(channels[k].name) - 1);
        ptrs[k] = reinterpret_cast<unsigned char*>(planes[k].data());
    }
    std::vector<std::pair<std::string, std::string>> attrs;
    attrs.emplace_back("vkpath.format", kFormat);
    attrs.emplace_back("vkpath.samples", std::to_string(state.firstSample) + ":" + std::to_string(state.nextSample));
    attrs.emplace_back("vkpath.samplesTaken", std::to_string(state.samplesTaken));
    attrs.emplace_back("vkpath.rays", std::to_string(state.counters.rays));
    attrs.emplace_back("vkpath.nonfinite", std::to_string(state.counters.nonfinite));
    attrs.emplace_back("vkpath.loopGuard", std::to_string(state.counters.loopGuard));
    if (!state.aov.empty()) attrs.emplace_back("vkpath.aovFrame", formatAovFrame(state.aovFrame));
    for (const auto& [name, value] : key.entries) attrs.emplace_back(keyAttributeName(name), value);
    std::vector<EXRAttribute> custom(attrs.size());
    for (std::size_t k = 0; k < attrs.size(); ++k) {
        std::memset(&custom[k], 0, sizeof(EXRAttribute));
        std::strncpy(custom[k].name, attrs[k].first.c_str(), sizeof(custom[k].name) - 1);
        std::strcpy(custom[k].type, "string");
        custom[k].value = reinterpret_cast<unsigned char*>(attrs[k].second.data());
        custom[k].size = int(attrs[k].second.size());
    }

    EXRHeader header;  // not HeaderGuard: the arrays are ours
    InitEXRHeader(&header);
    header.num_channels = int(maps.size());
    header.channels = channels.data();
    header.pixel_types = types.data();
    header.requested_pixel_types = types.data();
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
    header.num_custom_attributes = int(custom.size());
    header.custom_attributes = custom.data();
    EXRImage exr;
    InitEXRImage(&exr);
    exr.num_channels = int(maps.size());
    exr.images = ptrs.data();
    exr.width = int(state.width);
    exr.height = int(state.height);
    unsigned char* memory = nullptr;
    ExrError err;
    const std::size_t size = SaveEXRImageToMemory(&exr, &header, &memory, &err.msg);
    if (size == 0 || memory == nullptr) {
        std::free(memory);
        throw InputError(path.string() + ": cannot encode the accumulation EXR: " + err.text());
    }
    out.write(reinterpret_cast<const char*>(memory), std::streamsize(size));
    std::free(memory);
}

void writeAccumFile(const std::filesystem::path& path, const RenderKey& key, const RenderState& state) {
    writeFileAtomic(path, [&](std::ostream& out) { encodeAccumFile(out, path, key, state); });
}

AccumFile readAccumFile(const std::filesystem::path& path) {
    const std::string name = path.string();
    auto fail = [&](const std::string& what) -> void { throw InputError(name + ": " + what); };
    const std::vector<unsigned char> bytes = readInputBytes(path);  // a regular file only (core/input_file.h)

    EXRVersion version;
    if (ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()) != TINYEXR_SUCCESS)
        fail("not an OpenEXR file (bad or missing magic number)");
    if (version.multipart || version.non_image || version.tiled) fail("not a vkpath accumulation file (multi-part, deep or tiled EXR)");
    HeaderGuard header;
    ExrError err;
    if (ParseEXRHeaderFromMemory(&header.h, &version, bytes.data(), bytes.size(), &err.msg) != TINYEXR_SUCCESS)
        fail("invalid or truncated EXR header: " + err.text());
    std::map<std::string, std::string> attrs;
    for (int k = 0; k < header.h.num_custom_attributes; ++k) {
        const EXRAttribute& a = header.h.custom_attributes[k];
        if (std::strcmp(a.type, "string") == 0 && a.value && a.size >= 0)
            attrs[a.name] = std::string(reinterpret_cast<const char*>(a.value), std::size_t(a.size));
    }
    auto attr = [&](const std::string& key) -> const std::string& {
        const auto it = attrs.find(key);
        if (it == attrs.end()) fail("not a vkpath accumulation file (no attribute " + key + "; write one with --partial or --checkpoint)");
        return it->second;
    };
    if (attr("vkpath.format") != kFormat) fail("unknown accumulation format '" + attr("vkpath.format") + "' (this vkpath reads '" + kFormat + "')");

    AccumFile f;
    RenderState& st = f.state;
    const std::string& samples = attr("vkpath.samples");
    const std::size_t colon = samples.find(':');
    if (colon == std::string::npos) fail("attribute vkpath.samples is not A:B: '" + samples + "'");
    const std::uint64_t a = parseU64(path, "vkpath.samples", samples.substr(0, colon));
    const std::uint64_t b = parseU64(path, "vkpath.samples", samples.substr(colon + 1));
    if (a > b || b > 0xffffffffull) fail("attribute vkpath.samples is not a range A:B with A <= B: '" + samples + "'");
    st.firstSample = std::uint32_t(a);
    st.nextSample = std::uint32_t(b);
    st.samplesTaken = parseU64(path, "vkpath.samplesTaken", attr("vkpath.samplesTaken"));
    st.counters.rays = parseU64(path, "vkpath.rays", attr("vkpath.rays"));
    st.counters.nonfinite = parseU64(path, "vkpath.nonfinite", attr("vkpath.nonfinite"));
    st.counters.loopGuard = parseU64(path, "vkpath.loopGuard", attr("vkpath.loopGuard"));
    for (const auto& [k, v] : attrs) {
        if (k.rfind(kKeyPrefix, 0) != 0) continue;
        std::string entry = k.substr(std::strlen(kKeyPrefix));
        std::replace(entry.begin(), entry.end(), '_', ' ');
        f.key.entries.emplace_back(entry, v);
    }
    if (f.key.entries.empty()) fail("no key (attributes vkpath.key.*)");

    bool adaptive = false, aov = false;
    for (int c = 0; c < header.h.num_channels; ++c) {
        adaptive = adaptive || std::strcmp(header.h.channels[c].name, "active") == 0;
        aov = aov || std::strcmp(header.h.channels[c].name, "aov_samples") == 0;
        if (header.h.pixel_types[c] != TINYEXR_PIXELTYPE_FLOAT)
            fail(std::string("channel ") + header.h.channels[c].name + " is not 32-bit float");
    }
    ImageGuard exr;
    exr.i.num_channels = header.h.num_channels;  // see core/image_exr.cpp: tinyexr frees on failure
    if (LoadEXRImageFromMemory(&exr.i, &header.h, bytes.data(), bytes.size(), &err.msg) != TINYEXR_SUCCESS) {
        InitEXRImage(&exr.i);
        fail("invalid or truncated EXR pixel data: " + err.text());
    }
    if (exr.i.width <= 0 || exr.i.height <= 0 || !exr.i.images) fail("no pixels");
    st.width = std::uint32_t(exr.i.width);
    st.height = std::uint32_t(exr.i.height);
    const std::size_t n = std::size_t(st.pixels());
    st.sum.assign(n * kStateFloatsPerPixel, 0.0f);
    st.sumSq.assign(n * kStateFloatsPerPixel, 0.0f);
    if (adaptive) {
        st.decision.assign(n * kStateFloatsPerPixel, 0.0f);
        st.active.assign(n, 0);
    }
    // Feature sums written before the indirect moments (6fb8864) or the frame (16ef338) were kept:
    // named as such, not as a file that is no accumulation at all.
    auto older = [&](const std::string& what) {
        fail("its feature sums (--aov) are from an older vkpath: no " + what + "; render it again with this one");
    };
    if (aov) {
        if (attrs.find("vkpath.aovFrame") == attrs.end()) older("attribute vkpath.aovFrame");
        st.aov.assign(n * kAovFloatsPerPixel, 0.0f);
        const std::optional<AovFrame> frame = parseAovFrame(attr("vkpath.aovFrame"));
        if (!frame) fail("attribute vkpath.aovFrame is not 9 numbers: '" + attr("vkpath.aovFrame") + "'");
        st.aovFrame = *frame;
    }
    for (const ChannelMap& m : channelMaps(adaptive, aov)) {
        int index = -1;
        for (int c = 0; c < header.h.num_channels; ++c)
            if (m.name == header.h.channels[c].name) index = c;
        if (index < 0 && m.array == &RenderState::aov) older("channel " + m.name);
        if (index < 0 || !exr.i.images[index]) fail("no channel " + m.name);
        const float* plane = reinterpret_cast<const float*>(exr.i.images[index]);
        for (std::size_t i = 0; i < n; ++i) {
            if (m.array) (st.*m.array)[i * m.stride + m.offset] = plane[i];
            else st.active[i] = plane[i] != 0.0f;
        }
    }
    return f;
}

}  // namespace vkp
