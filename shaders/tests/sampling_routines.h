// Routine ids of the device test kernel shaders/tests/sampling_test.comp (its push constant
// `routine`; the I/O layout of each routine is at the top of that file), declared once for the
// kernel and for its C++ harness tests/gpu/sampling_kernel.h.
#ifndef VKP_SAMPLING_ROUTINES_H
#define VKP_SAMPLING_ROUTINES_H
#include "shared/glsl_compat.h"

VKP_BEGIN
const uint R_RNG = 0u;
const uint R_ONB = 1u;
const uint R_COSINE_HEMI = 2u;
const uint R_UNIFORM_SPHERE = 3u;
const uint R_UNIFORM_HEMI = 4u;
const uint R_UNIFORM_CONE = 5u;
const uint R_UNIFORM_DISK = 6u;
const uint R_UNIFORM_BALL = 7u;
const uint R_QUAD_LIGHT = 8u;
const uint R_TRI_LIGHT = 9u;
const uint R_SPHERE_LIGHT = 10u;
const uint R_LAMBERTIAN = 11u;
const uint R_METAL = 12u;
const uint R_DIELECTRIC = 13u;
const uint R_FRESNEL = 14u;
const uint R_RECT_LIGHT = 15u;
const uint R_GGX_VNDF = 16u;
const uint R_GLTF_SAMPLE = 17u;
const uint R_GLTF_EVAL = 18u;
const uint R_LIGHT_PICK = 19u;
const uint R_SPH_TRI_LIGHT = 20u;
const uint R_SOBOL = 21u;
VKP_END

#endif
