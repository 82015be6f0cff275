// Feature images (AOVs, `vkpath render --aov`): what each sample adds to its pixel's AOV sums, and
// the layout of those sums in the kernel's AOV buffer (binding VKP_BINDING_AOV). C++ and GLSL
// (shared/glsl_compat.h): the host's unit tests run these rules.
//
// Definitions (docs/design.md "Feature images"), as the denoisers that take such guides ask (Open
// Image Denoise's "albedo" and "normal" auxiliary images):
//   albedo   the reflectance of the path's first non-specular vertex: the colour of a lambertian
//            surface (its texture included), of a fuzzy metal, the base colour of a glTF
//            material, the single-scattering albedo of a medium; seen through perfect mirrors
//            (metal of fuzz 0) and glass, whose sampled weights tint it. A path that escapes, or
//            ends on a light, before such a vertex sees the radiance there clamped to [0, 1]
//            (the background, the emitter). Averaged over all of the pixel's samples.
//   normal   the unit shading normal at that vertex, on the side the path arrived from; (0,0,0)
//            for an escaped path, inside a medium, or when the path ended before such a vertex.
//            Averaged over all samples (so its length is below 1 where samples disagree).
//   position the first surface the camera ray hits (media ignored), in world units; averaged over
//            the samples that hit something ("hits"; the pixel has no position when none did).
//   emission the radiance a sample gathered before its first non-specular vertex or its first
//            glass vertex, whichever comes first (its whole radiance when it has neither): lights
//            and the background seen directly or through mirrors. It has no noise but the pixel
//            filter's, so the denoiser leaves it out of what it filters and adds it back. What is
//            seen through glass is not in it (aovEmissionStops): glass reflects or refracts by
//            chance, so a light seen through it is noise like any other (16 samples of a glass
//            sphere in front of a light: one reflects onto it and the pixel is a firefly), and
//            the denoiser filters it. Averaged over all samples (a sample the image drops as not
//            finite adds 0).
//   indirect the Rec. 709 luminance of the rest of the sample's radiance (radiance - emission),
//            its mean and the mean of its square over all samples (a dropped sample adds 0):
//            the variance the denoiser's edge-stopping needs is that of what it filters, which
//            the emission's pixel-coverage noise (at a light's edge, huge) must not inflate.
// depth is the position's distance along the camera's view axis, computed by the host from the
// mean position (it is linear in it); variance and spp come from the accumulation sums.
#ifndef VKP_AOV_H
#define VKP_AOV_H
#include "bsdf.h"
#include "glsl_compat.h"
#include "kinds.h"

VKP_BEGIN

/// vec4s per pixel in the AOV buffer: [k*i] = (mean albedo RGB, samples), [k*i+1] = (mean normal
/// XYZ, hits), [k*i+2] = (mean position XYZ over the hits, in camera-relative world units, mean
/// indirect luminance), [k*i+3] = (mean emission RGB, mean squared indirect luminance).
/// Running means, mean += (x - mean) / n after each sample (Welford 1962): a constant stays exact,
/// and rounding grows like sqrt(n) ulps where a float sum's grows like n ulps (2e-6 relative
/// after 256 samples of 0.9, which a sum gets; the mean gets 0).
const uint AOV_VEC4_PER_PIXEL = 4u;

/// A metal whose fuzz is at most this is a mirror for the AOVs: the path is followed through it.
const float AOV_MIRROR_FUZZ = 0.0f;

/// True if the AOVs look through BSDF b (a perfect mirror or glass) to the next vertex.
VKP_FN bool aovSeesThrough(Bsdf b) {
    if (b.type == MAT_DIELECTRIC) return true;
    return b.type == MAT_METAL && b.param <= AOV_MIRROR_FUZZ;
}

/// The emission feature (above) stops at a vertex with BSDF b: at every vertex the AOVs do not see
/// through, and at glass, whose sample is random (reflect or refract by Fresnel's odds), so what
/// the path gathers after it is noise for the denoiser to filter. A mirror's reflection is
/// deterministic: the lights seen in it stay emission, unfiltered and sharp.
VKP_FN bool aovEmissionStops(Bsdf b) { return !aovSeesThrough(b) || b.type == MAT_DIELECTRIC; }

/// The albedo AOV of a vertex with BSDF b that the AOVs do not see through (aovSeesThrough
/// false): a glTF material's base colour (texture and vertex colour applied), the albedo of the
/// other types (lambertian, fuzzy metal, a medium's phase function). Linear RGB.
VKP_FN vec3 aovAlbedo(Bsdf b) {
    if (b.type == MAT_PBR) return b.gltf.baseColor;
    return b.albedo;
}

/// The normal AOV of that vertex: the shading normal facing the arriving ray; 0 in a medium.
VKP_FN vec3 aovNormal(Bsdf b) {
    if (b.type == MAT_ISOTROPIC) return vec3(0.0f);
    vec3 n = b.frame.n;
    return dot(n, b.dIn) > 0.0f ? -n : n;
}

VKP_END

#endif
