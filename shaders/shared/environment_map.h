// The environment map: an equirectangular (latitude-longitude) image of the radiance arriving from
// infinitely far away, importance sampled with the 2D piecewise-constant distribution of
// distribution.h (pbrt-v4 sec. 12.5.3 uses the same scheme with pbrt-v3's lat-long mapping).
//
// Mapping, in the map's own frame (world frame when rotate_y = 0), y is up:
//   theta = pi v (v = 0: the top row of the image, +y; v = 1: the bottom row, -y),
//   phi = 2 pi u,   direction = (-sin(theta) sin(phi), cos(theta), sin(theta) cos(phi)),
// so u = 0.5 (the middle column) is -z (the view of the default camera looking at -z), u = 0.75
// is +x (to the right of that view) and u = 0 / 1 is +z (behind it). The image's u, v are the
// continuous coordinates of the image: pixel (i, j) covers [i, i+1)/W x [j, j+1)/H.
// rotate_y = a degrees turns the environment about +y like an object's rotate_y (x' = cos a x +
// sin a z, z' = -sin a x + cos a z): world = R(a) map, map = R(-a) world. cs = (cos a, sin a).
//
// Density: (u, v) are sampled with density p(u, v) on the unit square; d(omega) = sin(theta)
// dtheta dphi = 2 pi^2 sin(theta) du dv, so the solid-angle pdf is p(u, v) / (2 pi^2 sin(theta)).
// The host builds the distribution from luminance x the mean of sin(theta) over each row (> 0 even
// for the rows at the poles), so every texel with radiance has a density > 0 and nothing divides
// by zero; a direction exactly at a pole (sin(theta) = 0, a set of measure zero) gets pdf 0.
#ifndef VKP_ENVIRONMENT_MAP_H
#define VKP_ENVIRONMENT_MAP_H
#include "distribution.h"

VKP_BEGIN

/// Unit direction of map coordinates (u, v) in the map's frame.
VKP_FN vec3 envMapDirection(vec2 uv) {
    float theta = VKP_PI * uv.y;
    float phi = VKP_TWO_PI * uv.x;
    float st = sin(theta);
    return vec3(-st * sin(phi), cos(theta), st * cos(phi));
}

/// Map coordinates (u in [0,1), v in [0,1]) of a unit direction in the map's frame.
VKP_FN vec2 envMapUV(vec3 m) {
    float u = atan(-m.x, m.z) * (0.5f * VKP_INV_PI);  // (-0.5, 0.5]
    if (u < 0.0f) u += 1.0f;
    if (u >= 1.0f) u = 0.0f;  // u = -tiny + 1 rounds to 1
    float v = acos(min(max(m.y, -1.0f), 1.0f)) * VKP_INV_PI;
    return vec2(u, v);
}

/// World direction of a map-frame direction (rotation by rotate_y; cs = (cos, sin)).
VKP_FN vec3 envToWorld(vec3 m, vec2 cs) { return vec3(cs.x * m.x + cs.y * m.z, m.y, -cs.y * m.x + cs.x * m.z); }
/// Map-frame direction of a world direction (the inverse rotation).
VKP_FN vec3 envToMap(vec3 d, vec2 cs) { return vec3(cs.x * d.x - cs.y * d.z, d.y, cs.y * d.x + cs.x * d.z); }

/// Texel (column, row) of map coordinates in a w x h map (nearest: the texel that contains them).
VKP_FN uvec2 envTexel(vec2 uv, uint w, uint h) { return uvec2(distCellOf(uv.x, w), distCellOf(uv.y, h)); }

/// Solid-angle density of a direction whose (u, v) density is p, at sin(theta) = sinTheta.
VKP_FN float envSolidAnglePdf(float p, float sinTheta) {
    return (sinTheta > 0.0f) ? p / (2.0f * VKP_PI * VKP_PI * sinTheta) : 0.0f;
}

/// Samples a world direction from the w x h map's distribution (at base 0 of the table) with u in
/// [0,1)^2: the direction, its solid-angle pdf in pdf (0: no sample), its map coordinates in uv.
VKP_FN vec3 sampleEnvMap(VKP_DIST_PARAM uint w, uint h, vec2 cs, vec2 u, OUT(float) pdf, OUT(vec2) uv) {
    float puv;
    uv = sampleDistribution2D(VKP_DIST_ARG 0u, w, h, u, puv);
    vec3 m = envMapDirection(uv);
    pdf = envSolidAnglePdf(puv, sqrt(max(m.x * m.x + m.z * m.z, 0.0f)));
    return envToWorld(m, cs);
}

/// Solid-angle pdf with which sampleEnvMap produces the world direction d (unit).
VKP_FN float pdfEnvMap(VKP_DIST_PARAM uint w, uint h, vec2 cs, vec3 d) {
    vec3 m = envToMap(d, cs);
    vec2 uv = envMapUV(m);
    float sinTheta = sqrt(max(m.x * m.x + m.z * m.z, 0.0f));
    return envSolidAnglePdf(pdfDistribution2D(VKP_DIST_ARG 0u, w, h, uv), sinTheta);
}

VKP_END
#endif
