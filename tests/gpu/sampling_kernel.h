// Harness of the test_gpu_sampling*.cpp tests: runs the device test kernel
// shaders/tests/sampling_test.comp (the GLSL build of shaders/shared/{rng,onb,sampling,
// light_sampling,scatter,microfacet}.h; I/O layout and routine ids at its top) and its C++ twin (the same
// main() with vkp::gpu), and compares their outputs item by item.
#pragma once
#include <bit>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "tests/sampling_routines.h"
#include "vk/device.h"

namespace vkp::test::sampling {

using glm::vec2;
using glm::vec3;
using glm::vec4;

/// Routine ids of sampling_test.comp (push constant `routine`).
enum Routine : std::uint32_t {
    kRng = gpu::R_RNG, kOnb = gpu::R_ONB, kCosineHemi = gpu::R_COSINE_HEMI, kUniformSphere = gpu::R_UNIFORM_SPHERE,
    kUniformHemi = gpu::R_UNIFORM_HEMI, kUniformCone = gpu::R_UNIFORM_CONE, kUniformDisk = gpu::R_UNIFORM_DISK,
    kUniformBall = gpu::R_UNIFORM_BALL, kQuadLight = gpu::R_QUAD_LIGHT, kTriLight = gpu::R_TRI_LIGHT,
    kSphereLight = gpu::R_SPHERE_LIGHT, kLambertian = gpu::R_LAMBERTIAN, kMetal = gpu::R_METAL,
    kDielectric = gpu::R_DIELECTRIC, kFresnel = gpu::R_FRESNEL, kRectLight = gpu::R_RECT_LIGHT,
    kGgxVndf = gpu::R_GGX_VNDF, kGltfSample = gpu::R_GLTF_SAMPLE, kGltfEval = gpu::R_GLTF_EVAL,
    kLightPick = gpu::R_LIGHT_PICK, kSphTriLight = gpu::R_SPH_TRI_LIGHT, kSobol = gpu::R_SOBOL
};

/// Inputs in0..in3 of one item (binding 0: four vec4 per item).
struct Item {
    vec4 in[4]{vec4(0.0f), vec4(0.0f), vec4(0.0f), vec4(0.0f)};
};
/// Outputs out0, out1 of one item (binding 1: two vec4 per item).
struct Out {
    vec4 o[2]{vec4(0.0f), vec4(0.0f)};
};
static_assert(sizeof(Item) == 64 && sizeof(Out) == 32, "std430 vec4 arrays");

inline Item item(vec4 a, vec4 b = vec4(0.0f), vec4 c = vec4(0.0f), vec4 d = vec4(0.0f)) {
    Item it;
    it.in[0] = a;
    it.in[1] = b;
    it.in[2] = c;
    it.in[3] = d;
    return it;
}
inline vec3 xyz(const vec4& v) { return vec3(v.x, v.y, v.z); }
inline float asFloat(std::uint32_t b) { return std::bit_cast<float>(b); }
inline std::uint32_t asUint(float f) { return std::bit_cast<std::uint32_t>(f); }
/// Distance of x from the ends of [0,1].
inline double edgeDistance(double x) { return x < 1.0 - x ? x : 1.0 - x; }

constexpr float kBelowOne = 0x1.fffffep-1f;  ///< 1 - 2^-24, the largest u that rngNext returns
constexpr float kEdgeU[] = {0.0f, 0x1p-24f, 0.25f, 0.5f, 0.75f, kBelowOne};
constexpr double kPi = 3.14159265358979323846;
/// Random inputs per routine (besides the edge cases); the whole comparison takes < 1 s on lavapipe.
constexpr int kRandomItems = 20000;

// Tolerances shared by several routines. Measured on lavapipe (Mesa 22.3, LLVM 15): products,
// sums, divisions and sqrt agree bit for bit with the host (no fma contraction on either side);
// sin/cos differ by ~1 ulp, atan by up to ~3e-6 rad, normalize() by an ulp or two. Each tolerance
// below is ~10x or more the largest difference seen (the tests print "worst error/tolerance").
constexpr double kDirTol = 4e-6;  ///< unit vectors and points built with sin/cos, pow (seen: 6e-7)
constexpr double kInvTol = 1e-5;  ///< inverses of one input (atan; seen: 2.1e-6, the disk)
constexpr double kPdfRel = 2e-6;  ///< relative, pdfs of one input (seen: 6e-8)

/// Runs routine r on the device for every item (one dispatch, workgroups of 64).
std::vector<Out> runSamplingKernel(VulkanDevice& dev, Routine r, const std::vector<Item>& items);
/// The kernel's main() for one item, with the C++ build of the shared headers.
Out hostSamplingKernel(Routine r, const Item& it);
/// gtest expectation: the validation layer (on in GpuEnv) has said nothing so far.
void expectNoValidationMessages(VulkanDevice& dev);

/// Every pair of edge values kEdgeU, then n uniform pairs (UniformSource(seed)).
std::vector<vec2> uPairs(std::uint32_t seed, int n);
/// Axes, the troublesome normals of onbFromNormal (n.z = -1 + tiny, n.z = -0), then n uniform.
std::vector<vec3> unitNormals(std::uint32_t seed, int n);

/// Collects the comparisons of one routine: failures (with the item's inputs as hex floats, for
/// reproduction), accepted branch flips, and per field the largest error relative to its tolerance.
class Compare {
public:
    explicit Compare(std::string routine) : routine_(std::move(routine)) {}
    void item(std::size_t i, const Item& it) {
        index_ = i;
        item_ = &it;
    }
    void fail(const std::string& what);
    /// |device - host| <= absTol + relTol |host|.
    void near(const char* field, double dev, double host, double absTol, double relTol = 0.0);
    /// The same for a value on the circle [0,1) (an inverted azimuth u.y); dev must be in [0,1).
    void nearCircular(const char* field, double dev, double host, double tol);
    void bitsEqual(const char* field, float dev, float host);
    /// No NaN or Inf in either build's output.
    void finite(const Out& dev, const Out& host);
    /// A branch that rounding may decide either way went differently in the two builds.
    void flip() { ++flips_; }
    int failures() const { return failures_; }
    /// Prints the summary line; returns the first failures for the gtest message.
    std::string report(std::size_t items) const;

private:
    void note(const char* field, double err, double tol);
    std::string routine_;
    std::size_t index_ = 0;
    const Item* item_ = nullptr;
    int failures_ = 0, flips_ = 0;
    std::map<std::string, double> worst_;
    std::vector<std::string> examples_;
};

/// Compares one item's device output with the host's (and may evaluate host functions at the
/// device's output).
using Comparator = std::function<void(Compare&, const Item&, const Out& dev, const Out& host)>;

/// Runs routine r on the device, checks every output is finite in both builds, compares every
/// item with cmp, and expects no failure and no validation message.
void checkRoutine(VulkanDevice& dev, Routine r, const char* name, const std::vector<Item>& items, const Comparator& cmp);

/// A parallelogram / triangle light Q + a e1 + b e2 seen from p.
struct PlanarCase {
    vec3 q, e1, e2, p;
};
/// A sphere light (centre c, radius R) seen from p.
struct SphereCase {
    vec3 c;
    float R;
    vec3 p;
};

}  // namespace vkp::test::sampling
