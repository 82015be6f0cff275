// `vkpath merge PART... -o OUT`: the image of the union of sample ranges (render/merge.h).
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "core/errors.h"
#include "core/interrupt.h"
#include "render/aov.h"
#include "render/merge.h"
#include "render/session.h"

namespace vkp {

int runMerge(const CliArgs& a) {
    installInterruptHandlers();  // a signal during the writes still leaves no temporary file
    for (const auto& o : a.session.outputs) checkOutputPath(o);
    if (!a.session.partial.empty()) checkCanCreateFile(a.session.partial);
    std::vector<AccumFile> parts;
    std::vector<std::string> names;
    for (const auto& p : a.parts) {
        parts.push_back(readAccumFile(p));
        names.push_back(p.string());
    }
    const AccumFile merged = mergeParts(parts, names);
    const RenderState& st = merged.state;
    // Feature images: albedo, normal, depth, position and emission need the parts' AOV sums;
    // variance and spp come from the accumulation sums every part has.
    std::unique_ptr<FeatureImages> features;
    for (Aov v : a.session.aovs)
        if (aovNeedsKernel(v) && st.aov.empty())
            throw InputError("merge: --aov " + std::string(aovName(v)) + " needs parts rendered with --aov (" + names.front() +
                             " has no feature images)");
    if (!st.aov.empty()) features = std::make_unique<FeatureImages>(featureImages(st.aov, st.width, st.height, st.aovFrame));
    const PixelSums sums = st.pixelSums();
    WriteOptions wo;
    wo.exposure = a.session.exposure;
    wo.metadata = imageMetadata(st.firstSample, st.nextSample, 0);
    wo.layers = aovLayers(a.session.aovs, features.get(), sums);
    std::vector<AtomicWrite> more;
    if (!a.session.partial.empty())
        more.push_back({a.session.partial, [&](std::ostream& out) { encodeAccumFile(out, a.session.partial, merged.key, st); }});
    writeImages(sums.mean(), a.session.outputs, wo, std::move(more));
    if (!a.session.quiet) {
        std::fprintf(stderr, "vkpath: merged %zu parts: samples [%u:%u) of %ux%u pixels, %llu non-finite samples dropped\n", parts.size(),
                     st.firstSample, st.nextSample, st.width, st.height, static_cast<unsigned long long>(st.counters.nonfinite));
        for (const auto& o : a.session.outputs) std::fprintf(stderr, "vkpath: wrote %s\n", o.string().c_str());
        if (!a.session.partial.empty()) std::fprintf(stderr, "vkpath: wrote %s\n", a.session.partial.string().c_str());
    }
    return kExitOk;
}

}  // namespace vkp
