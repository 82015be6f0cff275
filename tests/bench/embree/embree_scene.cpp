#include "embree_scene.h"

#include <limits>
#include <stdexcept>

namespace vkp::embree_ref {

namespace {
std::string errorText(RTCError e) {
    switch (e) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
        default: return "unknown error";
    }
}

void check(RTCDevice device, const char* what) {
    RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree: ") + what + ": " + errorText(e));
}

/// Attaches a committed geometry of `type` with `count` primitives: fill(vertexBuffer, indexBuffer)
/// writes them (indexBuffer is null for spheres, which have none).
template <class Fill>
unsigned attach(RTCDevice device, RTCScene scene, RTCGeometryType type, std::size_t vertices, RTCFormat vertexFormat,
                std::size_t vertexBytes, std::size_t prims, RTCFormat indexFormat, std::size_t indexBytes, Fill fill) {
    RTCGeometry g = rtcNewGeometry(device, type);
    check(device, "rtcNewGeometry");
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, vertexFormat, vertexBytes, vertices));
    unsigned* idx = nullptr;
    if (indexBytes) idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, indexFormat, indexBytes, prims));
    check(device, "rtcSetNewGeometryBuffer");
    fill(v, idx);
    rtcCommitGeometry(g);
    unsigned id = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    check(device, "rtcAttachGeometry");
    return id;
}
}  // namespace

std::string embreeVersion() { return RTC_VERSION_STRING; }

EmbreeScene::EmbreeScene(const Scene& scene, const std::string& config) {
    device_ = rtcNewDevice(config.c_str());
    if (!device_) throw std::runtime_error("Embree: rtcNewDevice(\"" + config + "\"): " + errorText(rtcGetDeviceError(nullptr)));
    scene_ = rtcNewScene(device_);
    check(device_, "rtcNewScene");
    std::vector<std::uint32_t> tris, quads, spheres;
    for (std::uint32_t i = 0; i < scene.shapes.size(); ++i) {
        switch (scene.shapes[i].type) {
            case ShapeType::Triangle: tris.push_back(i); break;
            case ShapeType::Quad: quads.push_back(i); break;
            case ShapeType::Sphere: spheres.push_back(i); break;
        }
    }
    auto record = [&](unsigned id, std::vector<std::uint32_t> shapes) {
        if (shapeOf_.size() <= id) shapeOf_.resize(id + 1);
        shapeOf_[id] = std::move(shapes);
    };
    auto put = [](float* v, std::size_t at, glm::vec3 p) {
        v[3 * at] = p.x;
        v[3 * at + 1] = p.y;
        v[3 * at + 2] = p.z;
    };
    if (!tris.empty()) {
        unsigned id = attach(device_, scene_, RTC_GEOMETRY_TYPE_TRIANGLE, 3 * tris.size(), RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                             tris.size(), RTC_FORMAT_UINT3, 3 * sizeof(unsigned), [&](float* v, unsigned* idx) {
                                 for (std::size_t k = 0; k < tris.size(); ++k) {
                                     const Shape& s = scene.shapes[tris[k]];
                                     put(v, 3 * k, s.p0);
                                     put(v, 3 * k + 1, s.p1);
                                     put(v, 3 * k + 2, s.p2);
                                     for (unsigned c = 0; c < 3; ++c) idx[3 * k + c] = unsigned(3 * k + c);
                                 }
                             });
        record(id, std::move(tris));
    }
    if (!quads.empty()) {
        // Embree's quad: four vertices v0..v3 in order, split into triangles (v0, v1, v3), (v2, v3, v1).
        unsigned id = attach(device_, scene_, RTC_GEOMETRY_TYPE_QUAD, 4 * quads.size(), RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                             quads.size(), RTC_FORMAT_UINT4, 4 * sizeof(unsigned), [&](float* v, unsigned* idx) {
                                 for (std::size_t k = 0; k < quads.size(); ++k) {
                                     const Shape& s = scene.shapes[quads[k]];
                                     put(v, 4 * k, s.p0);
                                     put(v, 4 * k + 1, s.p0 + s.p1);
                                     put(v, 4 * k + 2, s.p0 + s.p1 + s.p2);
                                     put(v, 4 * k + 3, s.p0 + s.p2);
                                     for (unsigned c = 0; c < 4; ++c) idx[4 * k + c] = unsigned(4 * k + c);
                                 }
                             });
        record(id, std::move(quads));
    }
    if (!spheres.empty()) {
        // RTC_GEOMETRY_TYPE_SPHERE_POINT: one FLOAT4 vertex (centre x, y, z, radius) per sphere.
        unsigned id = attach(device_, scene_, RTC_GEOMETRY_TYPE_SPHERE_POINT, spheres.size(), RTC_FORMAT_FLOAT4,
                             4 * sizeof(float), spheres.size(), RTC_FORMAT_UNDEFINED, 0, [&](float* v, unsigned*) {
                                 for (std::size_t k = 0; k < spheres.size(); ++k) {
                                     const Shape& s = scene.shapes[spheres[k]];
                                     v[4 * k] = s.p0.x;
                                     v[4 * k + 1] = s.p0.y;
                                     v[4 * k + 2] = s.p0.z;
                                     v[4 * k + 3] = s.radius;
                                 }
                             });
        record(id, std::move(spheres));
    }
    rtcCommitScene(scene_);
    check(device_, "rtcCommitScene");
}

EmbreeScene::~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
}

bool EmbreeScene::intersect(glm::vec3 o, glm::vec3 d, Hit& hit) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);  // flags: RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT
    RTCRayHit rh;
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.tnear = 0.0f;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.time = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit.shape = shapeOf_[rh.hit.geomID][rh.hit.primID];
    hit.t = rh.ray.tfar;
    return true;
}

bool EmbreeScene::occluded(glm::vec3 o, glm::vec3 d, float tMax) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    r.org_x = o.x;
    r.org_y = o.y;
    r.org_z = o.z;
    r.tnear = 0.0f;
    r.dir_x = d.x;
    r.dir_y = d.y;
    r.dir_z = d.z;
    r.time = 0.0f;
    r.tfar = tMax;
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
    rtcOccluded1(scene_, &ctx, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf when the ray is occluded
}

}  // namespace vkp::embree_ref
