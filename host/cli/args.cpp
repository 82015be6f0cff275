#include "cli/args.h"

#include <charconv>
#include <cmath>

#include "core/errors.h"

namespace vkp {

namespace {
[[noreturn]] void usage(const std::string& what) { throw InputError("usage: " + what + " (see 'vkpath --help')"); }

std::uint32_t parseUint(const std::string& flag, const std::string& v, std::uint32_t min, std::uint32_t max) {
    std::uint64_t x = 0;
    auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
    if (ec != std::errc() || p != v.data() + v.size() || x < min || x > max)
        usage(flag + " wants a whole number in [" + std::to_string(min) + ", " + std::to_string(max) + "], got '" + v + "'");
    return std::uint32_t(x);
}

double parseDouble(const std::string& flag, const std::string& v, double min, double max) {
    double x = 0;
    auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
    if (ec != std::errc() || p != v.data() + v.size() || !std::isfinite(x) || x < min || x > max)
        usage(flag + " wants a number in [" + std::to_string(min) + ", " + std::to_string(max) + "], got '" + v + "'");
    return x;
}

/// "R,G,B" or one value V for grey: linear radiance, each finite and >= 0.
glm::vec3 parseColour(const std::string& flag, const std::string& v) {
    std::vector<float> c;
    std::size_t start = 0;
    while (c.size() < 4) {
        const std::size_t comma = v.find(',', start);
        const std::string part = v.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        double x = 0;
        auto [p, ec] = std::from_chars(part.data(), part.data() + part.size(), x);
        if (part.empty() || ec != std::errc() || p != part.data() + part.size() || !std::isfinite(x) || x < 0 || x > 4e15)
            usage(flag + " wants R,G,B (or one value for grey): linear radiance, each in [0, 4e15], got '" + v + "'");
        c.push_back(float(x));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (c.size() == 1) return glm::vec3(c[0]);
    if (c.size() != 3) usage(flag + " wants R,G,B (or one value for grey), got '" + v + "'");
    return glm::vec3(c[0], c[1], c[2]);
}
}  // namespace

const char* usageText() {
    return R"(vkpath: a headless path tracer on Vulkan compute

usage:
  vkpath render SCENE [options]        render a scene: .json, .gltf or .glb (default output: SCENE's name .png)
  vkpath info SCENE                    primitives, lights, BVH statistics, shader variant, and whether
                                       the render fits the device (takes --width, --height, --device)
  vkpath devices [--validate]          list Vulkan devices and why any is unusable
  vkpath merge PART... -o OUT          add up the partial files of sample ranges of one render (--partial);
                                       --aov LIST writes their feature images (parts rendered with --aov)
                                       into its image; also takes --partial FILE, --exposure, --quiet
  vkpath --help | --version

render options:
  -o FILE                 output image, repeatable; format by extension: .png .exr .pfm .hdr
  --spp N                 samples per pixel (overrides the scene)
  --time SECONDS          stop after this much wall time (whichever of --spp/--time comes first)
  --width N, --height N   image size (override the scene)
  --max-depth N           path length cap      --seed N   random seed
  --rr-depth N            Russian roulette from the Nth ray of a path on (default: the scene's, 3)
  --sampler S             bsdf | light | mixture (the book's) | mis (default)
  --sequence Q            sobol (default: Owen-scrambled Sobol' points) | random (independent numbers)
  --light-pick P          power (default: emitters in proportion to their power) | uniform
  --light-sampling L      quads/triangles: auto (default: solid angle where the light looks large, else
                          area) | solid-angle (wherever precise) | area (the book's)
  --solid-angle-min SR    auto's switch: solid angle from points where area/distance^2 >= SR (default 0.1)
  --workgroup WxH|auto    the kernel's workgroup size (W, H in 1-64, W*H <= 1024; default auto: from the
                          device's subgroup size, 8x8 for subgroups of up to 64 lanes)
  --tile-order O          scrambled (default: balances lavapipe's threads) | linear
  --variant V             auto (default: compile in only what the scene needs) | full
  --specialize W          host (default: the variant's constants baked into the kernel before the
                          driver compiles it: faster to compile) | driver (the same image)
  --cache-dir DIR|none    where compiled kernels are kept between runs (default $VKPATH_CACHE_DIR, else
                          $XDG_CACHE_HOME/vkpath or ~/.cache/vkpath); none: no cache
  --device SEL            device index or name substring (default: the most capable); render: 'all' or
                          a list (0,1) splits the samples over several devices and merges them
  --validate              enable VK_LAYER_KHRONOS_validation; any message is an error
  --gltf-scene N          .gltf/.glb: render scene N of the file (default: the file's default scene)
  --camera N              .gltf/.glb: view through camera N of the file (default: its first perspective camera)
  --background R,G,B      light for a scene that has none: escaping rays see this linear radiance (one
                          value: grey); replaces the scene's environment
  --environment FILE      light from an equirectangular map (.hdr, .exr, .pfm); replaces the scene's
  --environment-strength S, --environment-rotate DEG
                          scale the map's radiance, turn it about +y (that map, or the scene's own)
  --instancing M          glTF: auto (default: a mesh several nodes use, or of a file a JSON scene includes
                          several times, is stored once, two-level BVH) | flatten (every node's triangles
                          placed in the world); also for 'vkpath info'
  --spatial-splits        build the BVH with spatial splits (SBVH: a triangle may sit in several leaves):
                          fewer traversal steps where large or long triangles overlap others, a slower
                          build (docs/performance.md "Spatial splits"); also for 'vkpath info'
  --allow-path DIR        a folder (and those below it) that the scene's references may reach besides
                          the referring file's own: included glTF files, environment maps, glTF buffers
                          and images (repeatable; symbolic links are followed before the check)
  --exposure EV           exposure in stops for PNG output (default 0)
  --dump-every N          write the image every N spp into --dump-dir (default ./frames)
  --dump-dir DIR          folder of progressive frames: frame-<spp>.png
  --dump-format F         also dump exr or pfm (repeatable)
  --aov LIST              feature images: any of albedo,normal,depth,position,emission,variance,spp (or all),
                          as layers of EXR outputs (albedo.R, normal.X, ...; also in EXR dumps), else
                          as files OUT.<aov>.<ext> (.pfm beside a PNG); docs/design.md "Feature images"
  --denoise               also write a denoised image (biased; the raw image is kept): OUT.denoised.<ext>
                          beside every output, or --denoise-output FILE
  --denoise-output FILE   where the denoised image goes (with --denoise)
  --denoise-dumps         denoise every dump too: frame-<spp>.denoised.<ext> (with --denoise)
  --denoise-filter F      nlm (default: non-local means, then one a-trous level) or atrous (the
                          a-trous filter alone); docs/design.md "Denoiser"
  --samples-per-dispatch N  samples one dispatch adds per pixel, 1-64 (default: automatic, <= 32 on a
                            CPU device, <= 8 on a GPU)
  --pixels-per-invocation N  pixels one invocation takes in turn, 1-64 (default: automatic: on a
                            CPU device, several where a dispatch adds fewer samples per pixel than
                            --samples-per-dispatch, as in large images; the image is the same)
  --adaptive T            adaptive sampling: a pixel stops once its estimated relative standard error
                          (that of relMSE's (x-y)^2/(y^2+0.01)) is <= T, e.g. 0.02; unbiased: a quarter
                          of the samples only decide (docs/design.md "Adaptive sampling"); --spp is the maximum
  --adaptive-min-spp N    samples every pixel gets before the first decision (default 64)
  --reference REF         .exr/.pfm/.hdr of the same size: print the final error against it
  --error-log LOG.csv     with --reference: a row spp,seconds,rmse,relmse,mean_r,mean_g,mean_b
                          at every dump (or, without --dump-every, at 1,2,4,8,... spp) and at the end
  --stats-json FILE       the run's numbers (spp, rays, timings, rates, device) as JSON
  --quiet                 no progress output
  --checkpoint FILE       keep the render's state in FILE (an EXR of its sums; atomic): every
                          --checkpoint-every SECONDS (default 60), at SIGINT/SIGTERM and at the end
  --resume FILE           continue the checkpoint FILE of the same render (same scene and options; the
                          first difference is named); the result equals an uninterrupted render bit for bit
  --sample-range A:B      render samples A to B-1 of every pixel (B replaces --spp; not with --adaptive)
  --partial FILE.exr      write the raw sums (an EXR with the key and the range) for 'vkpath merge'

signals: SIGINT or SIGTERM finishes the batch in flight, writes every output (and --checkpoint,
--partial) with the samples reached, and exits 130 or 143; a second one exits at once, writing nothing

exit codes: 0 success, 1 bad input or usage, 2 no usable Vulkan device, 3 Vulkan failure
)";
}

CliArgs parseArgs(const std::vector<std::string>& args) {
    CliArgs a;
    if (args.empty()) return a;
    std::size_t i = 0;
    const std::string cmd = args[i++];
    if (cmd == "--help" || cmd == "-h" || cmd == "help") return a;
    if (cmd == "--version") {
        a.command = Command::Version;
        return a;
    }
    if (cmd == "render") a.command = Command::Render;
    else if (cmd == "info") a.command = Command::Info;
    else if (cmd == "devices") a.command = Command::Devices;
    else if (cmd == "merge") a.command = Command::Merge;
    else usage("unknown command '" + cmd + "'");

    auto value = [&](const std::string& flag) -> std::string {
        if (i >= args.size()) usage(flag + " needs a value");
        return args[i++];
    };
    auto fileValue = [&](const std::string& flag) -> std::string {
        std::string v = value(flag);
        if (v.empty()) usage(flag + " needs a file name");
        return v;
    };
    bool renderOnly = false;
    std::string renderOnlyFlag;  // the first render option that merge does not take
    std::string checkpointEveryFlag;
    bool solidAngleMinGiven = false;
    while (i < args.size()) {
        const std::string f = args[i++];
        if (f == "--validate") { a.validate = true; continue; }
        if (f == "--device") { a.device = value(f); continue; }
        if (f == "--gltf-scene") { a.gltfScene = parseUint(f, value(f), 0, 0x7fffffffu); continue; }
        if (f == "--camera") { a.camera = parseUint(f, value(f), 0, 0x7fffffffu); continue; }
        if (f == "--allow-path") { a.allowPaths.emplace_back(fileValue(f)); continue; }
        if (f == "--spatial-splits") { a.spatialSplits = true; continue; }
        if (f == "--instancing") {
            const std::string v = value(f);
            if (v == "flatten") a.instancing = false;
            else if (v == "auto") a.instancing = true;
            else usage("--instancing must be auto or flatten, got '" + v + "'");
            continue;
        }
        // Light for scenes that bring none: they change the variant and the device data, which
        // `vkpath info` shows, so both commands take them.
        if (f == "--background") { a.background = parseColour(f, value(f)); continue; }
        if (f == "--environment") { a.environment = fileValue(f); continue; }
        if (f == "--environment-strength") { a.environmentStrength = float(parseDouble(f, value(f), 0.0, 1e30)); continue; }
        if (f == "--environment-rotate") { a.environmentRotate = float(parseDouble(f, value(f), -1e6, 1e6)); continue; }
        // The image size decides whether a render fits the device: `vkpath info` checks it too.
        if (f == "--width") { a.width = parseUint(f, value(f), 1, 16384); continue; }
        if (f == "--height") { a.height = parseUint(f, value(f), 1, 16384); continue; }
        if (f == "--help" || f == "-h") { a.command = Command::Help; return a; }
        if (!f.empty() && f[0] == '-' && f != "-") {
            renderOnly = true;
            if (f != "-o" && f != "--partial" && f != "--exposure" && f != "--aov" && f != "--quiet" && f != "-q" && renderOnlyFlag.empty())
                renderOnlyFlag = f;
            if (f == "-o") a.session.outputs.emplace_back(value(f));
            else if (f == "--spp") a.spp = parseUint(f, value(f), 1, 1u << 24);
            else if (f == "--time") a.session.timeLimit = parseDouble(f, value(f), 1e-3, 1e7);
            else if (f == "--max-depth") a.maxDepth = parseUint(f, value(f), 1, 1024);
            else if (f == "--rr-depth") a.rouletteDepth = parseUint(f, value(f), 1, 1024);
            else if (f == "--seed") a.seed = parseUint(f, value(f), 0, 0xffffffffu);
            else if (f == "--sampler") {
                const std::string s = value(f);
                if (!parseSampler(s, a.render.sampler)) usage("--sampler must be bsdf, light, mixture or mis, got '" + s + "'");
            } else if (f == "--sequence") {
                const std::string s = value(f);
                if (!parseSequence(s, a.render.sequence)) usage("--sequence must be random or sobol, got '" + s + "'");
            } else if (f == "--light-pick") {
                const std::string s = value(f);
                if (!parseLightPick(s, a.render.lightPick)) usage("--light-pick must be power or uniform, got '" + s + "'");
            } else if (f == "--light-sampling") {
                const std::string s = value(f);
                if (!parseLightSampling(s, a.render.lightSampling))
                    usage("--light-sampling must be auto, solid-angle or area, got '" + s + "'");
            } else if (f == "--solid-angle-min") {
                a.render.solidAngleMinSize = float(parseDouble(f, value(f), 0.0, 1e3));
                solidAngleMinGiven = true;
            } else if (f == "--workgroup") {
                const std::string s = value(f);
                const std::size_t x = s.find('x');
                if (s == "auto") {
                    a.render.workgroupX = a.render.workgroupY = 0;
                } else {
                    if (x == std::string::npos) usage("--workgroup wants WxH, e.g. 16x8, or auto, got '" + s + "'");
                    a.render.workgroupX = parseUint(f, s.substr(0, x), 1, 64);
                    a.render.workgroupY = parseUint(f, s.substr(x + 1), 1, 64);
                    if (a.render.workgroupX * a.render.workgroupY > 1024)
                        usage("--workgroup: W*H must be at most 1024, got '" + s + "'");
                }
            } else if (f == "--tile-order") {
                const std::string s = value(f);
                if (s == "linear") a.render.linearTiles = true;
                else if (s == "scrambled") a.render.linearTiles = false;
                else usage("--tile-order must be scrambled or linear, got '" + s + "'");
            } else if (f == "--variant") {
                const std::string v = value(f);
                if (v == "full") a.render.fullVariant = true;
                else if (v != "auto") usage("--variant must be auto or full, got '" + v + "'");
            } else if (f == "--specialize") {
                const std::string v = value(f);
                if (v == "driver") a.render.specializeOnHost = false;
                else if (v != "host") usage("--specialize must be host or driver, got '" + v + "'");
            } else if (f == "--cache-dir") {
                const std::string v = fileValue(f);
                a.cacheDir = v == "none" ? std::filesystem::path() : std::filesystem::path(v);
            } else if (f == "--exposure") a.session.exposure = parseDouble(f, value(f), -64, 64);
            else if (f == "--dump-every") a.session.dumpEvery = parseUint(f, value(f), 1, 1u << 24);
            else if (f == "--dump-dir") a.session.dumpDir = value(f);
            else if (f == "--dump-format") {
                const std::string v = value(f);
                if (v == "exr") a.session.dumpFormats.push_back(ImageFormat::Exr);
                else if (v == "pfm") a.session.dumpFormats.push_back(ImageFormat::Pfm);
                else if (v == "hdr") a.session.dumpFormats.push_back(ImageFormat::Hdr);
                else if (v != "png") usage("--dump-format must be exr, pfm, hdr or png, got '" + v + "'");
            } else if (f == "--aov") {
                if (const std::string e = parseAovList(value(f), a.session.aovs); !e.empty()) usage("--aov: " + e);
            } else if (f == "--denoise") a.denoise = true;
            else if (f == "--denoise-output") a.session.denoiseOutput = fileValue(f);
            else if (f == "--denoise-dumps") a.session.denoiseDumps = true;
            else if (f == "--denoise-filter") {
                const std::string s = value(f);
                if (s == "nlm") a.denoiseFilter = DenoiseFilter::NonLocalMeans;
                else if (s == "atrous") a.denoiseFilter = DenoiseFilter::ATrous;
                else usage("--denoise-filter must be nlm or atrous, got '" + s + "'");
            }
            else if (f == "--samples-per-dispatch") a.render.samplesPerDispatch = parseUint(f, value(f), 1, 64);
            else if (f == "--pixels-per-invocation") a.render.pixelsPerInvocation = parseUint(f, value(f), 1, 64);
            else if (f == "--adaptive") a.render.adaptiveThreshold = parseDouble(f, value(f), 1e-6, 10);
            else if (f == "--adaptive-min-spp") a.render.adaptiveMinSpp = parseUint(f, value(f), 8, 1u << 24);
            else if (f == "--reference") a.reference = fileValue(f);
            else if (f == "--error-log") a.errorLog = fileValue(f);
            else if (f == "--stats-json") a.statsJson = fileValue(f);
            else if (f == "--quiet" || f == "-q") a.session.quiet = true;
            else if (f == "--checkpoint") a.session.checkpoint = fileValue(f);
            else if (f == "--checkpoint-every") {
                a.session.checkpointEvery = parseDouble(f, value(f), 1e-3, 1e7);
                checkpointEveryFlag = f;
            } else if (f == "--resume") a.resume = fileValue(f);
            else if (f == "--partial") a.session.partial = fileValue(f);
            else if (f == "--sample-range") {
                const std::string v = value(f);
                const std::size_t colon = v.find(':');
                if (colon == std::string::npos) usage("--sample-range wants A:B (samples A to B-1), got '" + v + "'");
                const std::uint32_t from = parseUint(f, v.substr(0, colon), 0, 1u << 24);
                const std::uint32_t to = parseUint(f, v.substr(colon + 1), 1, 1u << 24);
                if (from >= to) usage("--sample-range A:B wants A < B, got '" + v + "'");
                a.sampleRange.emplace(from, to);
            }
            else usage("unknown option '" + f + "'");
            continue;
        }
        if (a.command == Command::Merge) {
            a.parts.emplace_back(f);
            continue;
        }
        if (!a.scene.empty() || a.command == Command::Devices) usage("unexpected argument '" + f + "'");
        a.scene = f;
    }
    if (a.command == Command::Merge) {
        if (a.width || a.height || !a.device.empty() || a.validate || a.gltfScene || a.camera || a.background ||
            !a.environment.empty() || a.environmentStrength || a.environmentRotate || !a.instancing || a.spatialSplits)
            usage("vkpath merge takes -o, --partial, --aov, --exposure and --quiet only");
        if (!renderOnlyFlag.empty()) usage("vkpath merge takes -o, --partial, --aov, --exposure and --quiet, not " + renderOnlyFlag);
        if (a.parts.empty()) usage("vkpath merge needs partial files (written by vkpath render --partial)");
        if (a.session.outputs.empty() && a.session.partial.empty()) usage("vkpath merge needs -o OUT or --partial FILE");
        return a;
    }
    if ((a.command == Command::Render || a.command == Command::Info) && a.scene.empty())
        usage(std::string("vkpath ") + (a.command == Command::Render ? "render" : "info") + " needs a scene file");
    if (renderOnly && a.command != Command::Render) usage("render options are only valid with 'vkpath render'");
    if (!a.errorLog.empty() && a.reference.empty()) usage("--error-log needs --reference");
    if (a.background && !a.environment.empty()) usage("--background and --environment exclude each other (one environment light)");
    if (a.background && (a.environmentStrength || a.environmentRotate))
        usage("--environment-strength and --environment-rotate apply to a map, not to --background");
    if (!checkpointEveryFlag.empty() && a.session.checkpoint.empty()) usage("--checkpoint-every needs --checkpoint FILE");
    if (a.sampleRange && a.spp) usage("--sample-range A:B replaces --spp (its B is where the render stops)");
    if (a.sampleRange && a.render.adaptive())
        usage("--sample-range does not work with --adaptive: adaptive decisions need every earlier sample of a pixel");
    if (solidAngleMinGiven && a.render.lightSampling != LightSampling::Auto)
        usage("--solid-angle-min applies to --light-sampling auto only");
    if (!a.denoise && (!a.session.denoiseOutput.empty() || a.session.denoiseDumps || a.denoiseFilter))
        usage("--denoise-output, --denoise-dumps and --denoise-filter need --denoise");
    if (a.session.denoiseDumps && !a.session.dumpEvery) usage("--denoise-dumps needs --dump-every N");
    // The kernel gathers the feature images the AOVs or the denoiser need.
    for (Aov x : a.session.aovs) a.render.aov = a.render.aov || aovNeedsKernel(x);
    a.render.aov = a.render.aov || a.denoise;
    return a;
}

}  // namespace vkp
