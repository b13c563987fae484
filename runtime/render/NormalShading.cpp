#include "runtime/render/NormalShading.h"

#include <algorithm>
#include <cmath>

namespace kiosk::render {

float hybridGeometryWeight(float pixelsPerTexel, float tauTex) {
    if (!(tauTex > 0.0f) || !(pixelsPerTexel > 0.0f) || !std::isfinite(pixelsPerTexel)) return 0.0f;
    const float x = std::clamp(std::log2(pixelsPerTexel / tauTex), 0.0f, 1.0f);
    return x * x * (3.0f - 2.0f * x);
}

}  // namespace kiosk::render
