// Constant-density participating media ("Ray Tracing: The Next Week", sec. 9 "Volumes"; pbrt-v4
// sec. 11.1-11.2 for the radiometry): a region of space inside a convex boundary, with density
// sigma (extinction per world unit, the same for every wavelength) and an isotropic phase function
// whose albedo (scattered / extinguished) is a colour or a JSON texture. C++ and GLSL
// (shared/glsl_compat.h): the host's tests run the kernel's code.
//
// The boundary is a sphere or a box under an affine map, i.e. an ellipsoid or a parallelepiped:
// the record holds the map from camera-relative world space to the boundary's local space, where
// the region is the unit ball (MEDIUM_SPHERE) or the cube [-1, 1]^3 (MEDIUM_BOX). A ray's
// parameter t is the same in both spaces (the direction is mapped, not renormalised), so the
// interval where a ray is inside a medium comes from one analytic test, wherever the ray starts
// (inside too: a camera in fog), and no surface marks where a medium begins. Where media overlap
// their densities add (the book's result too: its media are independent objects, the nearest
// sampled event wins).
//
// Distances are sampled in proportion to the transmittance: free flight t = -ln(1 - u) / sigma
// (sampleFreeFlight), density sigma exp(-sigma t) (pdfFreeFlight), so that the weight of a
// scattering event is the albedo and that of passing a segment is 1 ("delta tracking" without
// null collisions: the density is constant).
#ifndef VKP_MEDIUM_H
#define VKP_MEDIUM_H
#include "glsl_compat.h"
#include "kinds.h"
#include "sampling.h"

VKP_BEGIN

/// One medium (4 texels, after the materials' tables in the materials buffer at
/// GpuFrame::media.y): rows r0..r2 of the affine map to the boundary's local space, local_i =
/// dot(r_i.xyz, x) + r_i.w for a camera-relative point x; params.x: density sigma (1/world unit,
/// > 0), params.y: bits of MEDIUM_SPHERE or MEDIUM_BOX, params.z: bits of the index of its
/// MAT_ISOTROPIC material (the albedo and its texture), params.w: 0.
struct GpuMedium {
    vec4 r0;
    vec4 r1;
    vec4 r2;
    vec4 params;
};
const uint GPU_MEDIUM_TEXELS = 4u;

/// Row r applied to point x (w = 1) or, with w = 0, to vector x.
VKP_FN float mediumRow(vec4 r, vec3 x, float w) { return r.x * x.x + r.y * x.y + r.z * x.z + r.w * w; }

/// The interval [t0, t1] of the ray o + t d (d need not be unit) inside medium m, clipped to
/// [tmin, tmax]; false when it is empty. A ray along a box face (or tangent to the ball) counts
/// as outside: that interval has no length.
VKP_FN bool mediumInterval(GpuMedium m, vec3 o, vec3 d, float tmin, float tmax, OUT(float) t0, OUT(float) t1) {
    vec3 ol = vec3(mediumRow(m.r0, o, 1.0f), mediumRow(m.r1, o, 1.0f), mediumRow(m.r2, o, 1.0f));
    vec3 dl = vec3(mediumRow(m.r0, d, 0.0f), mediumRow(m.r1, d, 0.0f), mediumRow(m.r2, d, 0.0f));
    t0 = tmin;
    t1 = tmax;
    if (floatBitsToUint(m.params.y) == MEDIUM_SPHERE) {
        // |ol + t dl|^2 = 1: a t^2 + 2 b t + c = 0 with the half coefficient b; the roots as
        // c / q and q / a (q = -b -+ sqrt(b^2 - a c)) lose no digits when |b| >> sqrt(a c).
        float a = dot(dl, dl);
        float b = dot(ol, dl);
        float c = dot(ol, ol) - 1.0f;
        float disc = b * b - a * c;
        if (!(disc > 0.0f) || !(a > 0.0f)) return false;
        float q = -(b + ((b < 0.0f) ? -1.0f : 1.0f) * sqrt(disc));
        float ra = q / a;
        float rb = (q != 0.0f) ? c / q : ra;
        t0 = max(t0, min(ra, rb));
        t1 = min(t1, max(ra, rb));
    } else {
        // Slabs |ol_i + t dl_i| <= 1 (Kay and Kajiya 1986); an axis the ray does not move along
        // is either inside its slab for every t or for none.
        for (int i = 0; i < 3; ++i) {
            float oi = (i == 0) ? ol.x : ((i == 1) ? ol.y : ol.z);
            float di = (i == 0) ? dl.x : ((i == 1) ? dl.y : dl.z);
            if (di == 0.0f) {
                if (!(abs(oi) < 1.0f)) return false;
                continue;
            }
            float ta = (-1.0f - oi) / di;
            float tb = (1.0f - oi) / di;
            t0 = max(t0, min(ta, tb));
            t1 = min(t1, max(ta, tb));
        }
    }
    return t0 < t1;
}

/// Free-flight distance in a medium of density sigma > 0 for u in [0,1): -ln(1 - u) / sigma,
/// distributed with density pdfFreeFlight.
VKP_FN float sampleFreeFlight(float sigma, float u) { return -log(1.0f - u) / sigma; }

/// Density of sampleFreeFlight at distance t >= 0: sigma exp(-sigma t) (per world unit).
VKP_FN float pdfFreeFlight(float sigma, float t) { return (t >= 0.0f) ? sigma * exp(-sigma * t) : 0.0f; }

/// Inverse of sampleFreeFlight: the u that gives distance t, 1 - exp(-sigma t).
VKP_FN float invertFreeFlight(float sigma, float t) { return 1.0f - exp(-sigma * t); }

/// Transmittance exp(-sigma L) of a segment of length L in a medium of density sigma: the
/// probability that sampleFreeFlight gives a distance beyond L.
VKP_FN float freeFlightTransmittance(float sigma, float len) { return exp(-sigma * len); }

/// The isotropic phase function ("The Next Week" sec. 9.2): a direction uniform on the unit
/// sphere for u in [0,1)^2 (sampleUniformSphere). Phase functions are normalised over the sphere,
/// so p(w) = 1/(4 pi) is both its value and its density: the sample's weight is the albedo.
VKP_FN vec3 sampleIsotropicPhase(vec2 u) { return sampleUniformSphere(u); }

/// Value and density of the isotropic phase function: 1/(4 pi) sr^-1 for every direction.
VKP_FN float pdfIsotropicPhase() { return pdfUniformSphere(); }

/// Inverse of sampleIsotropicPhase for a unit direction.
VKP_FN vec2 invertIsotropicPhase(vec3 w) { return invertUniformSphere(w); }

VKP_END
#endif
