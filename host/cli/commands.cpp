#include "cli/commands.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>

#include <sys/resource.h>

#include "bvh/flatten.h"
#include "bvh/two_level.h"
#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/huge_pages.h"
#include "core/interrupt.h"
#include "cli/multi_device.h"
#include "render/accum_file.h"
#include "cli/denoise_hook.h"
#include "render/render_key.h"
#include "render/error_metrics.h"
#include "render/features.h"
#include "render/gpu_arrays.h"
#include "render/render_job.h"
#include "render/renderer.h"
#include "render/run_stats.h"
#include "render/session.h"
#include "render/workgroup.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "vk/device.h"

namespace vkp {

namespace {
using Clock = std::chrono::steady_clock;

/// --spatial-splits: at most 30 % more primitive references (BvhBuildOptions::spatialSplits). The
/// suite's dense mesh used 0.8 % of it, the layout benchmark's 1M-triangle mesh 0.4 % under both
/// 0.3 and 1 (docs/performance.md "Spatial splits").
constexpr float kSpatialSplitBudget = 0.3f;

/// --background, --environment, --environment-strength, --environment-rotate applied to the loaded
/// scene (host/cli/args.h). Throws InputError with one line naming the option.
void applyLight(const CliArgs& a, Scene& s) {
    if (a.background) {
        s.render.background = *a.background;
        s.environment = Environment{};  // the constant background is now the environment
        return;
    }
    if (!a.environment.empty()) {
        try {
            s.environment = readEnvironmentMap(a.environment, a.environmentStrength.value_or(1.0f), a.environmentRotate.value_or(0.0f));
        } catch (const InputError& e) {
            throw InputError(std::string("--environment: ") + e.what());
        }
        return;
    }
    if (!a.environmentStrength && !a.environmentRotate) return;
    if (!s.environment.hasMap())
        throw InputError(std::string("usage: ") + (a.environmentStrength ? "--environment-strength" : "--environment-rotate") +
                         " needs an environment map: " + a.scene.string() + " has none (add --environment FILE)");
    if (a.environmentRotate) s.environment.rotateY = *a.environmentRotate;
    if (a.environmentStrength) {  // the map again, at the new strength
        try {
            s.environment = readEnvironmentMap(s.environment.file, *a.environmentStrength, s.environment.rotateY);
        } catch (const InputError& e) {
            throw InputError(s.environment.file.string() + ": " + e.what());
        }
    }
}

/// The scene has some light: an emitting surface (placed or instanced), a punctual light that is
/// not black, or environment light that is not black.
bool hasLight(const Scene& s) {
    for (const PunctualLight& l : s.punctualLights)
        if (l.intensity != glm::vec3(0.0f)) return true;
    bool emits = false;
    forEachShape(s, [&](const Shape& sh) { emits = emits || (sh.material < s.materials.size() && s.materials[sh.material].emits()); });
    if (emits || s.render.background != glm::vec3(0.0f)) return true;
    for (float x : s.environment.image.rgb)
        if (x > 0.0f) return true;
    return false;
}

/// The job of `vkpath render` / `vkpath info`: the scene by its extension (.gltf / .glb: glTF,
/// anything else: JSON) with the command line's overrides, and its options as parsed. Prints the
/// scene's warnings on stderr, and one when the scene has no light.
RenderJob makeJob(const CliArgs& a) {
    std::string ext = a.scene.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    const bool gltf = ext == ".gltf" || ext == ".glb";
    if (!gltf && (a.gltfScene || a.camera)) throw InputError("usage: --gltf-scene and --camera are for .gltf and .glb scenes");
    RenderJob job;
    job.sceneFile = a.scene;
    Scene& s = job.scene;
    if (gltf) {
        GltfOptions o;
        o.scene = a.gltfScene;
        o.camera = a.camera;
        o.width = a.width;  // one of them alone keeps the camera's aspect ratio
        o.height = a.height;
        o.instancing = a.instancing;
        o.allowPaths = a.allowPaths;
        s = loadSceneGltf(a.scene, o);
    } else {
        SceneJsonOptions o;
        o.instancing = a.instancing;  // included glTF files
        o.width = a.width;            // a scene without "camera" is framed for this size
        o.height = a.height;
        o.allowPaths = a.allowPaths;
        s = loadSceneJson(a.scene, o);
    }
    for (const std::string& w : s.warnings) std::fprintf(stderr, "vkpath: warning: %s\n", w.c_str());
    applyLight(a, s);
    if (!hasLight(s))
        std::fprintf(stderr,
                     "vkpath: warning: %s has no light (no emitting surface, no punctual light, no environment, a black background): the "
                     "image will be black; add --background R,G,B or --environment FILE\n",
                     a.scene.string().c_str());
    if (a.spp) s.render.spp = *a.spp;
    if (a.width) s.camera.width = *a.width;
    if (a.height) s.camera.height = *a.height;
    if (a.maxDepth) s.render.maxDepth = *a.maxDepth;
    if (a.rouletteDepth) s.render.rouletteDepth = *a.rouletteDepth;
    if (a.seed) s.render.seed = *a.seed;
    job.options = a.render;
    if (a.spatialSplits) job.bvh.spatialSplits = kSpatialSplitBudget;
    job.session = a.session;
    job.session.spp = a.sampleRange ? a.sampleRange->second : s.render.spp;
    // The default output, unless the render's result is its partial file (a sample range's).
    if (job.session.outputs.empty() && job.session.partial.empty()) job.session.outputs.push_back(a.scene.stem().string() + ".png");
    return job;
}

std::size_t countShapes(const Scene& s, ShapeType t) {
    std::size_t n = 0;
    for (const Shape& sh : s.shapes) n += sh.type == t;
    return n;
}

/// The folder of progressive dumps can take files: created if missing (the only thing made before
/// the render), refused when it is a file or cannot take one.
void checkDumpDir(const std::filesystem::path& dir) {
    std::error_code ec;
    if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
        throw InputError(dir.string() + ": --dump-dir is not a folder");
    std::filesystem::create_directories(dir, ec);
    if (ec) throw InputError(dir.string() + ": --dump-dir cannot be created: " + ec.message());
    checkCanCreateFile(dir / dumpFileName(0, ImageFormat::Png));
}
}  // namespace

int stoppedEarly(int signo) {
    std::fprintf(stderr, "vkpath: %s before the first sample: nothing written\n", signalName(signo));
    return exitCodeForSignal(signo);
}

int runRender(const CliArgs& a, Clock::time_point processStart) {
    installInterruptHandlers();
    auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
    auto t = Clock::now();
    RenderJob job = makeJob(a);
    const double secondsSceneLoad = since(t);
    // Fail before the render and leave no file: outputs, the reference, the logs, the state files.
    for (const auto& o : job.session.outputs) checkOutputPath(o);
    if (!job.session.denoiseOutput.empty()) checkOutputPath(job.session.denoiseOutput);
    if (!job.session.checkpoint.empty()) checkCanCreateFile(job.session.checkpoint);
    if (!job.session.partial.empty()) checkCanCreateFile(job.session.partial);
    if (job.session.dumpEvery) checkDumpDir(job.session.dumpDir);
    std::optional<AccumFile> resume;
    if (!a.resume.empty()) resume = readAccumFile(a.resume);
    std::optional<Image> reference;
    if (!a.reference.empty()) reference = readReferenceImage(a.reference, job.scene.camera.width, job.scene.camera.height);
    if (!a.errorLog.empty()) checkCanCreateFile(a.errorLog);
    if (!a.statsJson.empty()) checkCanCreateFile(a.statsJson);

    t = Clock::now();
    const FlatBvh bvh = buildSceneBvh(job.scene, job.bvh);
    const GpuArrays arrays = packGpuArrays(job.scene, bvh, job.options);
    const double secondsBvh = since(t);
    if (job.session.writesState() || resume) job.session.key = renderKey(arrays, job.options);  // SessionOptions::key
    job.session.aovFrame = arrays.aovFrame;
    const std::uint32_t firstSample = a.sampleRange ? a.sampleRange->first : 0;
    if (resume) {
        const std::string what = a.resume.string() + ": cannot resume";
        if (const std::string m = keyMismatch(resume->key, job.session.key); !m.empty()) throw InputError(what + ": " + m);
        const RenderState& st = resume->state;
        if (st.firstSample != firstSample)
            throw InputError(what + ": it holds samples from " + std::to_string(st.firstSample) + " on, this render starts at " +
                             std::to_string(firstSample) + (a.sampleRange ? "" : " (give its --sample-range)"));
        if (st.nextSample > job.session.spp)
            throw InputError(what + ": it already holds samples up to " + std::to_string(st.nextSample) + ", beyond this render's end " +
                             std::to_string(job.session.spp) + (a.sampleRange ? " (--sample-range)" : " (--spp)"));
    }
    if (const int sig = interruptSignal()) return stoppedEarly(sig);
    if (const std::vector<std::string> sel = deviceSelectors(a.device); sel.size() > 1 || sel[0] == "all")
        return renderOnDevices(a, job, arrays, firstSample, sel, processStart);
    t = Clock::now();
    VulkanInstance instance(a.validate);
    VulkanDevice device(instance, a.device);
    const std::shared_ptr<DiskCache> kernelCache = openKernelCache(a);
    device.useKernelCache(kernelCache);
    const double secondsSetup = since(t);
    // --denoise: the denoiser's pipelines once, used at the end (and at dumps or log rows).
    std::unique_ptr<Denoiser> denoiser;
    if (a.denoise) {
        denoiser = std::make_unique<Denoiser>(device, denoiseOptions(a.denoiseFilter));
        job.session.denoiser = denoiseHook(*denoiser);
    }
    t = Clock::now();
    Renderer renderer(device, arrays, job.options);  // refuses a render that does not fit the device
    if (resume) renderer.restore(resume->state, a.resume.string());
    else if (firstSample) renderer.startAt(firstSample);
    resume.reset();  // its arrays are on the device now
    const double secondsUpload = since(t);
    if (const int sig = interruptSignal()) return stoppedEarly(sig);
    if (!job.session.quiet)
        std::fprintf(stderr, "vkpath: %s, %ux%u, %u spp, device %s, variant %s\n", a.scene.string().c_str(),
                     job.scene.camera.width, job.scene.camera.height, job.session.spp, device.info().name.c_str(),
                     renderer.features().name().c_str());

    std::unique_ptr<ErrorLog> log;
    ErrorMetrics lastError, lastDenoisedError;
    if (reference) {
        const bool denoisedLog = job.session.denoiser != nullptr;
        if (!a.errorLog.empty()) log = std::make_unique<ErrorLog>(a.errorLog, denoisedLog);
        job.session.denoiseCheckpoints = denoisedLog && log;
        job.session.checkpointPowersOfTwo = true;
        job.session.onCheckpoint = [&, denoisedLog](const Checkpoint& c) {
            lastError = computeErrorMetrics(c.image, *reference);
            if (c.denoised) lastDenoisedError = computeErrorMetrics(*c.denoised, *reference);
            if (log && denoisedLog) log->append(c.spp, c.seconds, lastError, lastDenoisedError, c.denoiseSeconds);
            else if (log) log->append(c.spp, c.seconds, lastError);
        };
    }
    const SessionResult r = runSession(renderer, job.session, processStart);

    const double samples = double(r.samplesTaken);
    const double rs = std::max(r.renderSeconds, 1e-9);
    if (r.signal)
        std::fprintf(stderr, "vkpath: %s: stopped at sample %u of %u\n", signalName(r.signal), r.spp, job.session.spp);
    if (r.firstSample)
        std::fprintf(stderr, "vkpath: samples [%u:%u) of every pixel\n", r.firstSample, r.spp);
    std::fprintf(stderr,
                 "vkpath: %u spp in %.2f s (rendering %.2f s, first sample %.2f s): %.3f M samples/s, %.3f M rays/s, "
                 "%llu non-finite samples dropped\n",
                 r.spp - r.firstSample, r.seconds, r.renderSeconds, r.firstBatchSeconds, samples / rs / 1e6, double(r.counters.rays) / rs / 1e6,
                 static_cast<unsigned long long>(r.counters.nonfinite));
    if (renderer.adaptive())
        std::fprintf(stderr, "vkpath: adaptive sampling: %.1f samples per pixel on average, %u of %llu pixels still active\n",
                     double(r.samplesTaken) / double(std::max<std::uint64_t>(r.pixels, 1)), r.activePixels,
                     static_cast<unsigned long long>(r.pixels));
    if (r.nonfinitePixels)
        std::fprintf(stderr, "vkpath: warning: %llu pixels of the image are not finite (NaN or Inf)\n",
                     static_cast<unsigned long long>(r.nonfinitePixels));
    if (r.counters.loopGuard)
        std::fprintf(stderr, "vkpath: warning: %llu paths were cut short by the loop guard\n",
                     static_cast<unsigned long long>(r.counters.loopGuard));
    if (reference)
        std::fprintf(stderr, "vkpath: error against %s: rmse %.6g, relMSE %.6g\n", a.reference.string().c_str(),
                     lastError.rmse, lastError.relmse);
    for (const auto& o : job.session.outputs) std::fprintf(stderr, "vkpath: wrote %s\n", o.string().c_str());
    if (job.session.denoiser) {
        for (const auto& d : denoisedOutputs(job.session))
            std::fprintf(stderr, "vkpath: wrote %s (denoised in %.3f s: biased, the raw image is not)\n", d.string().c_str(), r.denoiseSeconds);
    }
    if (!job.session.partial.empty()) std::fprintf(stderr, "vkpath: wrote %s\n", job.session.partial.string().c_str());
    if (!job.session.checkpoint.empty())
        std::fprintf(stderr, "vkpath: wrote %s (checkpoint at sample %u)\n", job.session.checkpoint.string().c_str(), r.spp);
    if (log) std::fprintf(stderr, "vkpath: wrote %s (%zu rows)\n", a.errorLog.string().c_str(), log->rows());
    reportKernelCache(a, kernelCache.get());

    if (!a.statsJson.empty()) {
        RunStats st = runStats(job, renderer.features(), r);
        st.secondsSceneLoad = secondsSceneLoad;
        st.secondsBvh = secondsBvh;
        st.secondsSetup = secondsSetup;
        st.secondsUpload = secondsUpload;
        st.sceneBufferBytes = renderer.sceneBufferBytes();
        st.stagingCopies = device.stagingCopies();
        rusage ru{};
        if (getrusage(RUSAGE_SELF, &ru) == 0) st.peakRssBytes = std::uint64_t(ru.ru_maxrss) * 1024u;  // Linux: KiB
        st.hugePages = hugePagesRequested();
        st.spatialSplits = job.bvh.spatialSplits > 0.0f;
        if (kernelCache) {
            st.kernelCache = kernelCacheStats(*kernelCache);
            st.kernelCache->pipelineCacheBytesLoaded = device.pipelineCacheBytesLoaded();
        }
        st.bvhPrimitives = bvh.prims.size();
        const DeviceInfo& d = device.info();
        st.deviceName = d.name;
        st.deviceType = kindName(d.kind);
        st.driverName = d.driverName;
        st.driverInfo = d.driverInfo;
        st.vulkanVersion = apiVersionString(d.apiVersion);
        st.subgroupSize = d.subgroupSize;
        if (const char* v = std::getenv("LP_NUM_THREADS")) st.lpNumThreads = v;
        if (const char* v = std::getenv("MESA_SHADER_CACHE_DIR")) st.mesaShaderCacheDir = v;
        if (reference) {
            st.error = lastError;
            st.reference = a.reference.string();
        }
        st.secondsTotal = since(processStart);  // the stats file itself is not counted
        writeRunStatsJson(st, a.statsJson);
        std::fprintf(stderr, "vkpath: wrote %s\n", a.statsJson.string().c_str());
    }
    return r.signal ? exitCodeForSignal(r.signal) : kExitOk;
}

namespace {
/// The scene's shapes plus each instanced mesh's triangles (stored once): what a BVH without
/// spatial splits holds besides its instance primitives.
std::size_t primitivesBeforeSplits(const Scene& s) {
    std::size_t n = s.shapes.size();
    for (const InstancedMesh& m : s.meshes) n += m.shapes.size();
    return n;
}

std::string megabytes(std::uint64_t bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f MB", double(bytes) / 1e6);
    return buf;
}
}  // namespace

int runInfo(const CliArgs& a) {
    const RenderJob job = makeJob(a);
    const Scene& scene = job.scene;
    const FlatBvh bvh = buildSceneBvh(scene, job.bvh);
    const GpuArrays arrays = packGpuArrays(scene, bvh, job.options);
    const Features& f = arrays.features;
    std::printf("scene        %s\n", a.scene.string().c_str());
    std::printf("image        %ux%u, %u spp, max depth %u, seed %u\n", scene.camera.width, scene.camera.height,
                scene.render.spp, scene.render.maxDepth, scene.render.seed);
    std::printf("frame        camera-relative: origin at the camera, the file's point (%.17g, %.17g, %.17g)\n",
                scene.origin.x, scene.origin.y, scene.origin.z);
    const std::size_t moving = std::size_t(std::count_if(scene.shapes.begin(), scene.shapes.end(), [](const Shape& s) { return s.moves(); }));
    std::printf("primitives   %zu (%zu spheres, %zu quads, %zu triangles)", scene.shapes.size(),
                countShapes(scene, ShapeType::Sphere), countShapes(scene, ShapeType::Quad),
                countShapes(scene, ShapeType::Triangle));
    if (moving) std::printf(", %zu moving (motion blur)", moving);
    std::printf("\n");
    std::size_t emitters = 0;
    for (std::uint32_t l : scene.lights) emitters += scene.materials[scene.shapes[l].material].emits();
    std::printf("lights       %zu sampled objects (%zu emitting)", scene.lights.size(), emitters);
    std::size_t punctual[gpu::PUNCTUAL_KIND_COUNT] = {};
    for (const PunctualLight& l : scene.punctualLights) ++punctual[std::uint32_t(l.kind)];
    for (std::uint32_t k = 0; k < gpu::PUNCTUAL_KIND_COUNT; ++k)
        if (punctual[k]) std::printf(", %zu %s", punctual[k], gpu::kPunctualKindNames[k]);
    std::printf("\n");
    std::printf("materials    %zu\n", scene.materials.size());
    if (!scene.media.empty()) {
        std::size_t spheres = 0;
        for (const Medium& m : scene.media) spheres += m.boundary == Medium::Boundary::Sphere;
        std::printf("media        %zu constant-density (%zu in spheres, %zu in boxes), each tested along every ray\n",
                    scene.media.size(), spheres, scene.media.size() - spheres);
    }
    std::printf("bvh          %zu nodes, %zu leaves, depth %u, SAH cost %.3f, built in %.2f ms\n", bvh.stats.nodeCount,
                bvh.stats.leafCount, bvh.stats.maxDepth, bvh.stats.sahCost, bvh.stats.buildMs);
    if (job.bvh.spatialSplits > 0.0f)
        std::printf("spatial      splits on: %zu primitive references on the device for %zu shapes and mesh triangles\n",
                    bvh.prims.size() - std::size_t(bvh.stats.instanceCount), primitivesBeforeSplits(scene));
    // Geometry on the device: the BVH nodes, the primitives, the instances and (when the variant
    // reads them) the vertex-attribute records, as the packing step sizes them.
    std::uint64_t geometry = 0;
    for (const BufferSize& s : arrays.sizes())
        if (s.binding->binding == VKP_BINDING_NODES || s.binding->binding == VKP_BINDING_PRIMS ||
            s.binding->binding == VKP_BINDING_INSTANCES || (f.vertexAttributes && s.binding->binding == VKP_BINDING_ATTRIBUTES) ||
            (f.motion && s.binding->binding == VKP_BINDING_MOTION))
            geometry += s.bytes;
    if (scene.instances.empty()) {
        std::printf("instancing   none (%s): geometry on the device %s\n",
                    a.instancing ? "no glTF mesh is shared by two nodes" : "--instancing flatten", megabytes(geometry).c_str());
    } else {
        // Flattened, every instance carries its own copy of its mesh's triangles (and attribute
        // records), with about as many 4-wide nodes per triangle as this BVH has: an estimate.
        std::vector<std::size_t> meshPrims(scene.meshes.size(), 0);
        for (std::size_t i = 0; i < bvh.prims.size(); ++i)
            if (!bvh.primMesh.empty() && bvh.primMesh[i] > 0) ++meshPrims[bvh.primMesh[i] - 1];
        std::size_t storedPrims = 0, instancedTriangles = 0;
        for (std::size_t n : meshPrims) storedPrims += n;
        for (const MeshInstance& inst : scene.instances) instancedTriangles += meshPrims[inst.mesh];
        const double nodesPerPrim = double(arrays.nodes.size()) / double(std::max<std::size_t>(arrays.prims.size(), 1));
        const double perPrim = sizeof(gpu::GpuPrim) + (f.vertexAttributes ? gpu::ATTR_TEXELS * 16.0 : 0.0) +
                               nodesPerPrim * sizeof(gpu::GpuWideNode);
        const double flatBytes = double(geometry) - double(bvh.instances.size() * (sizeof(gpu::GpuInstance) + sizeof(gpu::GpuPrim))) +
                                 double(instancedTriangles - storedPrims) * perPrim;
        std::printf("instancing   %zu instances of %zu shared meshes (%zu triangles stored, %zu drawn), %zu top-level primitives\n",
                    scene.instances.size(), scene.meshes.size(), storedPrims, instancedTriangles + scene.shapes.size(),
                    bvh.stats.topPrimCount);
        std::printf("memory       geometry on the device %s two-level (auto); flattened (--instancing flatten) about %.2f MB\n",
                    megabytes(geometry).c_str(), flatBytes / 1e6);
    }
    std::printf("device data  %s of scene buffers, %s of per-pixel buffers at %ux%u\n", megabytes(arrays.sceneBytes()).c_str(),
                megabytes(arrays.pixelBytes()).c_str(), scene.camera.width, scene.camera.height);
    std::printf("variant      %s\n", f.name().c_str());
    // The device check a render makes before it allocates anything (fitProblem, planBands): the
    // same device (--device), its own limits. A scene is still described without a device.
    std::optional<VulkanInstance> instance;
    try {
        instance.emplace(a.validate);
    } catch (const DeviceError& e) {
        if (a.validate) throw;  // asked for the validation layer: its absence is an error, as for a render
        std::printf("device       none: %s\n", e.what());
        return kExitOk;
    }
    const DeviceChoice choice = selectDevice(instance->devices(), a.device);
    if (!choice.index && !a.device.empty()) throw DeviceError(choice.error);  // --device names none
    if (!choice.index) {
        std::printf("device       none usable: %s\n", choice.error.c_str());
        return kExitOk;
    }
    const DeviceInfo& d = instance->devices()[*choice.index];
    const DeviceLimits limits = deviceLimits(d);
    if (const std::string problem = fitProblem(arrays, limits); !problem.empty()) {
        std::printf("device       %s: the render does not fit\n", d.name.c_str());
        std::fprintf(stderr, "vkpath: error: %s\n", problem.c_str());
        return kExitNoDevice;
    }
    const std::size_t bands = planBands(arrays, limits).size();
    const glm::uvec2 wg = kernelWorkgroup(arrays.features, limits);
    std::printf("device       %s: fits (%zu band%s of rows; storage-buffer range %s, texel-buffer elements %llu); "
                "workgroup %ux%u%s, subgroups of %u lanes\n",
                d.name.c_str(), bands, bands == 1 ? "" : "s", megabytes(limits.maxStorageBufferRange).c_str(),
                static_cast<unsigned long long>(limits.maxTexelBufferElements), wg.x, wg.y,
                arrays.features.workgroupX ? "" : " (auto)", d.subgroupSize);
    return kExitOk;
}

int runDevices(const CliArgs& a) {
    VulkanInstance instance(a.validate);
    const auto& devs = instance.devices();
    if (devs.empty()) throw DeviceError("no Vulkan device found (install a driver: apt-get install mesa-vulkan-drivers)");
    const DeviceChoice def = selectDevice(devs, a.device);
    for (const DeviceInfo& d : devs) {
        const std::string why = unusableReason(d);
        std::printf("%u%s %s\n    type %s, driver %s%s%s, Vulkan %s, subgroups of %u lanes, %s%s\n", d.index,
                    def.index && *def.index == d.index ? " (default)" : "", d.name.c_str(), kindName(d.kind),
                    d.driverName.empty() ? "?" : d.driverName.c_str(), d.driverInfo.empty() ? "" : " / ",
                    d.driverInfo.c_str(), apiVersionString(d.apiVersion).c_str(), d.subgroupSize,
                    d.mappedBuffers ? "buffers mapped (unified memory)" : "buffers through staging copies",
                    why.empty() ? "" : (", unusable: " + why).c_str());
    }
    return def.index ? kExitOk : kExitNoDevice;
}

}  // namespace vkp
