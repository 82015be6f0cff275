// Point, spot and directional lights on the host: their emitted power (for the light pick) and the
// one check of their parameters that both loaders (JSON, glTF) use.
#include "scene/punctual_light.h"

#include <cmath>
#include <numbers>

#include "shared/punctual_light.h"

namespace vkp {

namespace {
double luminance(glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }
}  // namespace

double PunctualLight::power(double sceneRadius) const {
    const double pi = std::numbers::pi;
    const double lum = luminance(intensity);
    switch (kind) {
    case Kind::Point: return 4.0 * pi * lum;
    case Kind::Spot: {
        const float cosOuter = std::cos(outerCone);
        return 2.0 * pi * lum * double(gpu::spotSolidAngleOver2Pi(cosOuter, gpu::spotScale(std::cos(innerCone), cosOuter)));
    }
    case Kind::Directional: return pi * sceneRadius * sceneRadius * lum;
    }
    return 0.0;
}

std::string punctualLightProblem(const PunctualLight& l) {
    for (int c = 0; c < 3; ++c) {
        if (!(l.intensity[c] >= 0.0f) || !std::isfinite(l.intensity[c]))
            return "its intensity must be finite and >= 0 in every channel (after the unit conversion)";
    }
    if (!allFinite(l.position)) return "its position is outside the range of 32-bit floats relative to the camera";
    const float len = glm::length(l.direction);
    if (l.kind != PunctualLight::Kind::Point && !(std::abs(len - 1.0f) < 1e-3f))
        return "its direction is zero or not finite (a node scaled to nothing?)";
    return {};
}

}  // namespace vkp
