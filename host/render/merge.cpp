#include "render/merge.h"

#include <algorithm>
#include <numeric>

#include "core/errors.h"

namespace vkp {

namespace {
std::string range(const RenderState& s) {
    std::string r = "[";  // appended piecewise: GCC 12's -Wrestrict misfires on "[" + string&&
    r += std::to_string(s.firstSample);
    r += ":";
    r += std::to_string(s.nextSample);
    r += ")";
    return r;
}
}  // namespace

RenderState addStates(const std::vector<const RenderState*>& states, std::uint32_t firstSample, std::uint32_t nextSample) {
    RenderState m;
    m.width = states.front()->width;
    m.height = states.front()->height;
    m.firstSample = firstSample;
    m.nextSample = nextSample;
    const std::size_t floats = std::size_t(m.pixels()) * kStateFloatsPerPixel;
    m.sum.assign(floats, 0.0f);
    m.sumSq.assign(floats, 0.0f);
    std::vector<double> total(floats / 2);
    for (std::vector<float> RenderState::*array : {&RenderState::sum, &RenderState::sumSq}) {
        std::fill(total.begin(), total.end(), 0.0);
        for (const RenderState* s : states) {
            const std::vector<float>& a = s->*array;
            for (std::size_t i = 0; i < total.size(); ++i) {
                const std::size_t px = i / 4, c = i % 4;
                total[i] += double(a[px * 8 + c]) + double(a[px * 8 + 4 + c]);
            }
        }
        std::vector<float>& dst = m.*array;
        for (std::size_t i = 0; i < total.size(); ++i) {
            const std::size_t px = i / 4, c = i % 4;
            const float hi = float(total[i]);
            dst[px * 8 + c] = hi;
            dst[px * 8 + 4 + c] = float(total[i] - double(hi));
        }
    }
    // Feature images (every part has them or none: the key says so): shared/aov.h's running means
    // and counts, combined as means weighted by their counts, in double.
    if (!states.front()->aov.empty()) {
        const std::size_t n = states.front()->aov.size();
        // shared/aov.h: floats 3 and 7 are the counts (samples, hits); the position (8-10) is a
        // mean over the hits, every other float a mean over the samples.
        const auto countOf = [](std::size_t k) -> std::size_t { return k >= 8 && k < 11 ? 7 : 3; };
        const auto isCount = [](std::size_t k) { return k == 3 || k == 7; };
        std::vector<double> aov(n, 0.0);
        for (const RenderState* s : states) {
            if (s->aov.size() != n) throw InputError("merge: some parts have feature images (--aov) and some have not");
            for (std::size_t p = 0; p < n; p += kAovFloatsPerPixel)
                for (std::size_t k = 0; k < kAovFloatsPerPixel; ++k)
                    aov[p + k] += isCount(k) ? s->aov[p + k] : double(s->aov[p + countOf(k)]) * s->aov[p + k];
        }
        m.aov.assign(n, 0.0f);
        m.aovFrame = states.front()->aovFrame;  // one render (the key says so): one frame
        for (std::size_t p = 0; p < n; p += kAovFloatsPerPixel)
            for (std::size_t k = 0; k < kAovFloatsPerPixel; ++k) {
                const double count = aov[p + countOf(k)];
                m.aov[p + k] = isCount(k) ? float(aov[p + k]) : count > 0.0 ? float(aov[p + k] / count) : 0.0f;
            }
    }
    for (const RenderState* s : states) {
        m.samplesTaken += s->samplesTaken;
        m.counters.rays += s->counters.rays;
        m.counters.nonfinite += s->counters.nonfinite;
        m.counters.loopGuard += s->counters.loopGuard;
    }
    return m;
}

AccumFile mergeParts(const std::vector<AccumFile>& parts, const std::vector<std::string>& names) {
    if (parts.empty()) throw InputError("merge: no parts");
    const AccumFile& p0 = parts[0];
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const RenderState& s = parts[i].state;
        if (s.adaptive())
            throw InputError(names[i] + ": has adaptive sampling, whose parts cannot be merged (its pixels stopped at different samples)");
        if (i == 0) continue;
        if (const std::string m = keyMismatch(parts[i].key, p0.key); !m.empty())
            throw InputError(names[i] + ": a different render than " + names[0] + ": " + m);
        if (s.width != p0.state.width || s.height != p0.state.height)
            throw InputError(names[i] + ": " + std::to_string(s.width) + "x" + std::to_string(s.height) + ", " + names[0] + " is " +
                             std::to_string(p0.state.width) + "x" + std::to_string(p0.state.height));
    }
    // In the order of their ranges (empty ranges first), so that the input order does not matter.
    std::vector<std::size_t> order(parts.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const RenderState &x = parts[a].state, &y = parts[b].state;
        return x.firstSample != y.firstSample ? x.firstSample < y.firstSample : x.nextSample < y.nextSample;
    });
    for (std::size_t k = 1; k < order.size(); ++k) {
        const std::size_t a = order[k - 1], b = order[k];
        const RenderState &x = parts[a].state, &y = parts[b].state;
        if (y.firstSample < x.nextSample)
            throw InputError(names[b] + ": samples " + range(y) + " overlap " + names[a] + "'s " + range(x));
        if (y.firstSample > x.nextSample)
            throw InputError(names[b] + ": samples " + range(y) + " leave a gap after " + names[a] + "'s " + range(x) + ": samples [" +
                             std::to_string(x.nextSample) + ":" + std::to_string(y.firstSample) + ") are in no part");
    }
    AccumFile out;
    out.key = p0.key;
    std::vector<const RenderState*> states;
    for (std::size_t k : order) states.push_back(&parts[k].state);
    out.state = addStates(states, parts[order.front()].state.firstSample, parts[order.back()].state.nextSample);
    return out;
}

}  // namespace vkp
