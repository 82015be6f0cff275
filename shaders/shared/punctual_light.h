// Punctual lights: point, spot and directional lights, as glTF's KHR_lights_punctual defines them
// (and the JSON scenes' point_light, spot_light, directional_light). They are delta lights: a point
// light is a single point, a directional light a single direction, so no ray can hit one and no
// BSDF sample can find one; next-event estimation is their only strategy, under every sampler
// (pbrt-v4, "Physically Based Rendering", 4th ed., sec. 12.1 and 12.4). Their "sample" is the one
// direction, with the incident radiance integrated over the delta, i.e. the irradiance at the
// shading point from a surface facing the light: intensity x falloff / distance^2 for point and
// spot lights (W/sr / m^2), the irradiance itself for a directional light (W/m^2).
//
// Units: radiometric, linear RGB. glTF gives candela (point, spot) and lux (directional); the
// loaders divide by 683 lm/W (host/scene/gltf_lights.cpp, docs/gltf.md).
//
// The spot's falloff is the one the KHR_lights_punctual specification gives: with
// s = 1 / max(0.001, cos(inner) - cos(outer)) and c the cosine between the spot's axis and the
// direction from the light to the point, the intensity is scaled by clamp((c - cos(outer)) s, 0, 1)^2.
// C++ and GLSL (glsl_compat.h): the host's tests run the kernel's code.
#ifndef VKP_PUNCTUAL_LIGHT_H
#define VKP_PUNCTUAL_LIGHT_H
#include "gpu_types.h"
#include "kinds.h"

VKP_BEGIN

/// The spot falloff of KHR_lights_punctual at cosine c from the axis: clamp((c - cosOuter) s, 0, 1)^2
/// with s = 1 / max(0.001, cosInner - cosOuter) (spotScale). In [0, 1]; 1 inside the inner cone.
VKP_FN float spotFalloff(float c, float cosOuter, float scale) {
    float a = clamp((c - cosOuter) * scale, 0.0f, 1.0f);
    return a * a;
}

/// The falloff's scale for cone cosines cosInner > cosOuter (the specification's
/// lightAngleScale): 1 / max(0.001, cosInner - cosOuter).
VKP_FN float spotScale(float cosInner, float cosOuter) { return 1.0f / max(0.001f, cosInner - cosOuter); }

/// The solid-angle integral of spotFalloff over the sphere divided by 2 pi, exactly:
/// (1 - c1) + (c1 - cosOuter)^3 / (3 w^2) with w = 1 / scale and c1 = min(1, cosOuter + w), the
/// cosine where the falloff reaches 1. A spot of intensity I emits 2 pi I times this (W); a point
/// light (no cone) emits 4 pi I.
VKP_FN float spotSolidAngleOver2Pi(float cosOuter, float scale) {
    float w = 1.0f / scale;
    float c1 = min(1.0f, cosOuter + w);
    float r = c1 - cosOuter;
    return (1.0f - c1) + r * r * r / (3.0f * w * w);
}

/// The one sample of punctual light l (record layout: shared/gpu_types.h GpuPunctualLight) from the
/// shading point x: the unit direction towards the light, the irradiance it brings to a surface
/// facing it (le: intensity x falloff / distance^2, or a directional light's irradiance; 0 where a
/// spot does not reach), and the distance to the light (VKP_FAR for a directional light). valid is
/// false when x is at the light's position (no direction).
struct PunctualSample {
    vec3 dir;
    vec3 le;
    float dist;
    bool valid;
};

VKP_FN PunctualSample samplePunctualLight(GpuPunctualLight l, vec3 x) {
    PunctualSample s;
    uint kind = floatBitsToUint(l.q0.w);
    vec3 intensity = vec3(l.q1.x, l.q1.y, l.q1.z);
    if (kind == PUNCTUAL_DIRECTIONAL) {
        s.dir = vec3(l.q0.x, l.q0.y, l.q0.z);  // towards the light
        s.dist = VKP_FAR;
        s.le = intensity;
        s.valid = true;
        return s;
    }
    vec3 d = vec3(l.q0.x, l.q0.y, l.q0.z) - x;
    float d2 = dot(d, d);
    s.valid = d2 > 0.0f && d2 < VKP_FAR;
    s.dist = s.valid ? sqrt(d2) : 0.0f;
    s.dir = s.valid ? d / s.dist : vec3(0.0f, 0.0f, 1.0f);
    s.le = s.valid ? intensity / d2 : vec3(0.0f);
    if (kind == PUNCTUAL_SPOT) {
        vec3 axis = vec3(l.q2.x, l.q2.y, l.q2.z);  // the way the spot points
        s.le *= spotFalloff(-dot(axis, s.dir), l.q2.w, l.q1.w);
    }
    return s;
}

VKP_END
#endif
