#include "render/render_options.h"

namespace vkp {

const char* samplerName(Sampler s) {
    switch (s) {
        case Sampler::Bsdf: return "bsdf";
        case Sampler::Light: return "light";
        case Sampler::Mixture: return "mixture";
        default: return "mis";
    }
}

bool parseSampler(const std::string& name, Sampler& out) {
    if (name == "bsdf") out = Sampler::Bsdf;
    else if (name == "light") out = Sampler::Light;
    else if (name == "mixture") out = Sampler::Mixture;
    else if (name == "mis") out = Sampler::Mis;
    else return false;
    return true;
}

const char* sequenceName(Sequence s) { return s == Sequence::Random ? "random" : "sobol"; }

bool parseSequence(const std::string& name, Sequence& out) {
    if (name == "random") out = Sequence::Random;
    else if (name == "sobol") out = Sequence::Sobol;
    else return false;
    return true;
}

const char* lightPickName(LightPick p) { return p == LightPick::Uniform ? "uniform" : "power"; }

bool parseLightPick(const std::string& name, LightPick& out) {
    if (name == "power") out = LightPick::Power;
    else if (name == "uniform") out = LightPick::Uniform;
    else return false;
    return true;
}

const char* lightSamplingName(LightSampling s) {
    switch (s) {
        case LightSampling::Area: return "area";
        case LightSampling::SolidAngle: return "solid-angle";
        case LightSampling::Auto: return "auto";
    }
    return "?";
}

bool parseLightSampling(const std::string& name, LightSampling& out) {
    if (name == "auto") out = LightSampling::Auto;
    else if (name == "solid-angle") out = LightSampling::SolidAngle;
    else if (name == "area") out = LightSampling::Area;
    else return false;
    return true;
}

}  // namespace vkp
