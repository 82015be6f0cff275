#include "render/features.h"

#include <bit>
#include <cstdio>

#include "render/environment.h"
#include "render/texture_pack.h"

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

std::vector<std::uint32_t> Features::specConstants() const {
    return {spheres, parallelograms, lambertian, metal, dielectric, emitters,
            sphereLights, quadLights, std::uint32_t(sampler), defocus, environment, environmentMap, pbr,
            vertexAttributes, textures, alpha, std::uint32_t(sequence), lightSampling != LightSampling::Area,
            instances, workgroupX, workgroupY,
            std::bit_cast<std::uint32_t>(lightSampling == LightSampling::Auto ? solidAngleMinSize : 0.0f),
            triangleLights, extensionTextures, texCoord1};
}

std::string Features::name() const {
    std::string prims, mats, lights;
    auto add = [](std::string& s, bool on, const char* what) {
        if (!on) return;
        if (!s.empty()) s += '+';
        s += what;
    };
    add(prims, spheres, "sphere");
    add(prims, parallelograms, "quad/triangle");
    add(mats, lambertian, "lambertian");
    add(mats, metal, "metal");
    add(mats, dielectric, "dielectric");
    add(mats, pbr, "pbr");
    add(mats, emitters, "emission");
    add(lights, sphereLights, "sphere");
    add(lights, quadLights, "quad");
    add(lights, triangleLights, "triangle");
    std::string out = "prims:";
    out += prims.empty() ? "none" : prims;
    out += " materials:";
    out += mats.empty() ? "none" : mats;
    out += " lights:";
    out += lights.empty() ? "none" : lights;
    out += " sampler:";
    out += samplerName(sampler);
    out += " sequence:";
    out += sequenceName(sequence);
    if (lightSampling != LightSampling::Auto) out += std::string(" light-sampling:") + lightSamplingName(lightSampling);
    if (lightSampling == LightSampling::Auto && solidAngleMinSize != kSolidAngleMinSize) {
        char buf[48];
        std::snprintf(buf, sizeof buf, " solid-angle-min:%g", double(solidAngleMinSize));
        out += buf;
    }
    if (defocus) out += " defocus";
    if (environment) out += environmentMap ? " env:map" : " env:constant";
    if (vertexAttributes) out += " vertex-attributes";
    if (textures) out += " textures";
    if (extensionTextures) out += " extension-textures";
    if (texCoord1) out += " texcoord1";
    if (alpha) out += " alpha";
    if (instances) out += " instances";
    return out;
}

Features sceneFeatures(const Scene& scene, Sampler sampler, bool full) {
    Features f;
    f.sampler = sampler;
    if (full) {
        f.spheres = f.parallelograms = f.lambertian = f.metal = f.dielectric = f.emitters = f.pbr = true;
        f.sphereLights = f.quadLights = f.triangleLights = f.defocus = f.environment = f.environmentMap = true;
        f.vertexAttributes = f.textures = f.extensionTextures = f.texCoord1 = f.alpha = f.instances = true;
        return f;
    }
    std::vector<bool> used(scene.materials.size(), false);
    forEachShape(scene, [&](const Shape& s) {
        (s.type == ShapeType::Sphere ? f.spheres : f.parallelograms) = true;
        used[s.material] = true;
        if (s.sampled) {
            if (s.type == ShapeType::Sphere) f.sphereLights = true;
            else if (s.type == ShapeType::Quad) f.quadLights = true;
            else f.triangleLights = true;
        }
    });
    f.instances = !scene.instances.empty();
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const Material m = kernelMaterial(scene.materials[i]);  // what the kernel renders it as
        f.lambertian |= m.type == MaterialType::Lambertian;
        f.metal |= m.type == MaterialType::Metal;
        f.dielectric |= m.type == MaterialType::Dielectric;
        f.pbr |= m.type == MaterialType::Pbr;
        if (transmissionTextured(m)) {  // glass (or metal) where its texture says so
            const Material t = transmittedMaterial(m);
            f.dielectric |= t.type == MaterialType::Dielectric;
            f.metal |= t.type == MaterialType::Metal;
        }
        f.emitters |= m.emits() || m.type == MaterialType::DiffuseLight;  // diffuse_light never scatters
    }
    f.defocus = scene.camera.defocusAngle > 0.0f;
    f.environment = hasEnvironmentLight(scene);
    f.environmentMap = scene.environment.hasMap();
    f.textures = sceneHasTextures(scene);
    f.extensionTextures = sceneHasExtensionTextures(scene);
    f.texCoord1 = f.textures && sceneHasTexCoord1(scene);
    f.alpha = sceneHasAlpha(scene);
    f.vertexAttributes = f.textures || f.alpha || sceneHasVertexAttributes(scene);  // textures need the UVs
    return f;
}

}  // namespace vkp
