#include "render/run_stats.h"

#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <ostream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/disk_cache.h"
#include "render/features.h"
#include "render/render_job.h"

namespace vkp {

namespace {
std::string num(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}
std::string num(std::uint64_t v) { return std::to_string(v); }
/// A float as its shortest round-trip decimal form (0.2, not 0.200000003).
std::string numFloat(float v) {
    if (!std::isfinite(v)) return "null";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    for (int digits = 1; digits < 9; ++digits) {
        char shorter[40];
        std::snprintf(shorter, sizeof shorter, "%.*g", digits, double(v));
        if (std::strtof(shorter, nullptr) == v) return shorter;
    }
    return buf;
}
double rate(double count, double seconds) { return seconds > 0.0 ? count / seconds : NAN; }

/// Writes `"key": value` lines with commas between them.
class ObjectWriter {
public:
    ObjectWriter(std::ostringstream& out, int indent) : out_(out), pad_(std::size_t(indent), ' ') { out_ << "{"; }
    void raw(const char* key, const std::string& value) {
        out_ << (first_ ? "\n" : ",\n") << pad_ << "  " << jsonString(key) << ": " << value;
        first_ = false;
    }
    void str(const char* key, const std::string& v) { raw(key, jsonString(v)); }
    void close() { out_ << "\n" << pad_ << "}"; }

private:
    std::ostringstream& out_;
    std::string pad_;
    bool first_ = true;
};
}  // namespace

std::string jsonString(const std::string& s) {
    std::string r = "\"";
    for (unsigned char c : s) {
        if (c == '"') r += "\\\"";
        else if (c == '\\') r += "\\\\";
        else if (c == '\n') r += "\\n";
        else if (c == '\t') r += "\\t";
        else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            r += buf;
        } else r += char(c);
    }
    return r + "\"";
}

RunStats::KernelCache kernelCacheStats(const DiskCache& cache) {
    RunStats::KernelCache k;
    k.dir = cache.dir().string();
    const DiskCache::Counts c = cache.counts();
    k.hits = c.hits;
    k.misses = c.misses;
    k.stores = c.stores;
    k.failedStores = c.failedStores;
    return k;
}

RunStats runStats(const RenderJob& job, const Features& kernel, const SessionResult& r) {
    const RenderOptions& o = job.options;
    RunStats st;
    st.version = VKPATH_VERSION;
    st.scene = job.sceneFile.string();
    st.frameOrigin = job.scene.origin;
    st.sampler = samplerName(o.sampler);
    st.sequence = sequenceName(o.sequence);
    st.lightPick = lightPickName(o.lightPick);
    st.lightSampling = lightSamplingName(o.lightSampling);
    st.solidAngleMinSize = o.lightSampling == LightSampling::Auto ? o.solidAngleMinSize : 0.0f;
    st.workgroup = std::to_string(kernel.workgroupX) + "x" + std::to_string(kernel.workgroupY);
    st.tileOrder = o.linearTiles ? "linear" : "scrambled";
    st.variant = kernel.name();
    st.fullVariant = o.fullVariant;
    st.width = job.scene.camera.width;
    st.height = job.scene.camera.height;
    st.maxDepth = job.scene.render.maxDepth;
    st.seed = job.scene.render.seed;
    st.samplesPerDispatch = o.samplesPerDispatch;
    st.adaptiveThreshold = o.adaptiveThreshold;
    st.sppRequested = job.session.spp;
    st.timeLimit = job.session.timeLimit;
    st.spp = r.spp;
    st.samplesTaken = r.samplesTaken;
    st.activePixels = r.activePixels;
    st.rays = r.counters.rays;
    st.firstBatchRays = r.firstBatchRays;
    st.nonfinite = r.counters.nonfinite;
    st.nonfinitePixels = r.nonfinitePixels;
    st.loopGuard = r.counters.loopGuard;
    st.secondsFirstBatch = r.firstBatchSeconds;
    st.secondsRender = r.renderSeconds;
    st.secondsLongestDispatch = r.longestDispatchSeconds;
    st.pixelsPerInvocation = r.pixelsPerInvocation;
    st.secondsToFirstSample = r.firstSampleAt;
    st.secondsCheckpoints = r.checkpointSeconds;
    st.secondsOutput = r.outputSeconds;
    st.checkpoints = r.checkpoints;
    return st;
}

std::string runStatsJson(const RunStats& s) {
    const double samples = double(s.samples());
    const double steadySeconds = s.secondsRender - s.secondsFirstBatch;
    const double steadySamples = samples - (s.spp > 0 ? double(s.pixels()) : 0.0);  // the first batch is 1 spp
    std::ostringstream out;
    ObjectWriter w(out, 0);
    w.str("vkpath_version", s.version);
    w.str("scene", s.scene);
    {
        char buf[96];  // %.17g: the double round-trips
        std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", s.frameOrigin.x, s.frameOrigin.y, s.frameOrigin.z);
        w.raw("frame_origin", buf);
    }
    w.raw("width", num(std::uint64_t(s.width)));
    w.raw("height", num(std::uint64_t(s.height)));
    w.raw("pixels", num(s.pixels()));
    w.raw("max_depth", num(std::uint64_t(s.maxDepth)));
    w.raw("seed", num(std::uint64_t(s.seed)));
    w.str("sampler", s.sampler);
    w.str("sequence", s.sequence);
    w.str("light_pick", s.lightPick);
    w.str("light_sampling", s.lightSampling);
    w.raw("solid_angle_min_size", numFloat(s.solidAngleMinSize));
    w.str("workgroup", s.workgroup);
    w.str("tile_order", s.tileOrder);
    w.str("variant", s.variant);
    w.raw("variant_full", s.fullVariant ? "true" : "false");
    w.raw("samples_per_dispatch", num(std::uint64_t(s.samplesPerDispatch)));
    w.raw("pixels_per_invocation", num(std::uint64_t(s.pixelsPerInvocation)));
    w.raw("spp_requested", num(std::uint64_t(s.sppRequested)));
    w.raw("time_limit", num(s.timeLimit));
    w.raw("spp", num(std::uint64_t(s.spp)));
    w.raw("samples", num(s.samples()));
    w.raw("mean_spp", num(s.pixels() ? double(s.samples()) / double(s.pixels()) : 0.0));
    w.raw("adaptive_threshold", num(s.adaptiveThreshold));
    w.raw("active_pixels", num(std::uint64_t(s.activePixels)));
    w.raw("rays", num(s.rays));
    w.raw("rays_first_batch", num(s.firstBatchRays));
    w.raw("nonfinite_samples", num(s.nonfinite));
    w.raw("nonfinite_pixels", num(s.nonfinitePixels));
    w.raw("loop_guard_paths", num(s.loopGuard));
    w.raw("seconds_total", num(s.secondsTotal));
    w.raw("seconds_scene_load", num(s.secondsSceneLoad));
    w.raw("seconds_bvh_build", num(s.secondsBvh));
    w.raw("seconds_setup", num(s.secondsSetup));
    w.raw("seconds_upload", num(s.secondsUpload));
    w.raw("seconds_first_batch", num(s.secondsFirstBatch));
    w.raw("seconds_render", num(s.secondsRender));
    w.raw("seconds_longest_dispatch", num(s.secondsLongestDispatch));
    w.raw("seconds_to_first_sample", num(s.secondsToFirstSample));
    w.raw("seconds_checkpoints", num(s.secondsCheckpoints));
    w.raw("seconds_output", num(s.secondsOutput));
    w.raw("checkpoints", num(std::uint64_t(s.checkpoints)));
    w.raw("peak_rss_bytes", num(s.peakRssBytes));
    w.raw("huge_pages", s.hugePages ? "true" : "false");
    w.raw("spatial_splits", s.spatialSplits ? "true" : "false");
    w.raw("bvh_primitives", num(s.bvhPrimitives));
    w.raw("scene_buffer_bytes", num(s.sceneBufferBytes));
    w.raw("staging_copies", num(s.stagingCopies));
    if (s.kernelCache) {
        std::ostringstream c;
        ObjectWriter cw(c, 2);
        cw.str("dir", s.kernelCache->dir);
        cw.raw("hits", num(s.kernelCache->hits));
        cw.raw("misses", num(s.kernelCache->misses));
        cw.raw("stores", num(s.kernelCache->stores));
        cw.raw("failed_stores", num(s.kernelCache->failedStores));
        cw.raw("pipeline_cache_bytes_loaded", num(s.kernelCache->pipelineCacheBytesLoaded));
        cw.close();
        w.raw("kernel_cache", c.str());
    } else {
        w.raw("kernel_cache", "null");
    }
    w.raw("samples_per_second", num(rate(samples, s.secondsRender)));
    w.raw("rays_per_second", num(rate(double(s.rays), s.secondsRender)));
    w.raw("samples_per_second_steady", num(rate(steadySamples, steadySeconds)));
    w.raw("rays_per_second_steady", num(rate(double(s.rays - s.firstBatchRays), steadySeconds)));
    {
        std::ostringstream d;
        ObjectWriter dw(d, 2);
        dw.str("name", s.deviceName);
        dw.str("type", s.deviceType);
        dw.str("driver", s.driverName);
        dw.str("driver_info", s.driverInfo);
        dw.str("vulkan", s.vulkanVersion);
        dw.raw("subgroup_size", num(std::uint64_t(s.subgroupSize)));
        dw.close();
        w.raw("device", d.str());
    }
    {
        std::ostringstream e;
        ObjectWriter ew(e, 2);
        ew.str("LP_NUM_THREADS", s.lpNumThreads);
        ew.str("MESA_SHADER_CACHE_DIR", s.mesaShaderCacheDir);
        ew.close();
        w.raw("environment", e.str());
    }
    if (s.error) {
        std::ostringstream e;
        ObjectWriter ew(e, 2);
        ew.str("reference", s.reference);
        ew.raw("rmse", num(s.error->rmse));
        ew.raw("relmse", num(s.error->relmse));
        ew.raw("mean_r", num(s.error->mean[0]));
        ew.raw("mean_g", num(s.error->mean[1]));
        ew.raw("mean_b", num(s.error->mean[2]));
        ew.close();
        w.raw("error", e.str());
    } else {
        w.raw("error", "null");
    }
    w.close();
    out << "\n";
    return out.str();
}

void writeRunStatsJson(const RunStats& stats, const std::filesystem::path& path) {
    const std::string text = runStatsJson(stats);
    writeFileAtomic(path, [&](std::ostream& o) { o << text; });
}

}  // namespace vkp
