#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/topo/Hillshade.h"
#include "runtime/topo/RasterView.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace kiosk::topo {

/**
 * @brief Byte encodings of unit surface normals (east, north, up), for dynamic lighting
 * (Döllner §7.4: the shader takes dot(normal, light) per texel).
 */
enum class NormalEncoding {
    /// 3 bytes: round((n * 0.5 + 0.5) * 255) for (east, north, up). Up is always > 0, so the
    /// blue byte of a valid texel is >= 128; (0, 0, 0) is reserved for nodata.
    /// GLSL: n = normalize(texel.rgb * 2.0 - 1.0).
    Rgb8,
    /// 2 bytes: upper-hemisphere octahedral map p = (e, n) / (|e| + |n| + up), rotated by 45
    /// degrees to fill the square: q = (p.x + p.y, p.x - p.y), bytes round((q * 0.5 + 0.5) *
    /// 255). (0, 0) would be a horizontal normal, so it is reserved for nodata.
    /// GLSL: q = texel.rg * 2.0 - 1.0; p = 0.5 * vec2(q.x + q.y, q.x - q.y);
    /// n = normalize(vec3(p, 1.0 - abs(p.x) - abs(p.y))).
    Octahedral8,
};

/** @brief Bytes per texel of an encoding (3 or 2). */
int bytesPerTexel(NormalEncoding encoding);

/** @brief Gradient and edge settings of a normal map (same meaning as in HillshadeParams). */
struct NormalMapParams {
    double zFactor = 1.0;
    double scale = 1.0;
    GradientAlgorithm algorithm = GradientAlgorithm::Horn;
    bool computeEdges = true;  ///< default on: a normal map has no reason to lose its border
    NormalEncoding encoding = NormalEncoding::Rgb8;
};

/**
 * @brief Per-pixel unit normals of the view's window, from the same gradient as the hillshade
 * (so Lambert of a decoded normal with the hillshade light reproduces the hillshade up to
 * encoding error): n = normalize(-dz/dEast, -dz/dNorth, 1) with heights * zFactor / scale.
 *
 * Writes width x height texels of bytesPerTexel(encoding) bytes at out + r * outStride
 * (outStride in bytes). Nodata texels are all-zero bytes. Errors as hillshade()
 * (TOPO_INVALID_VIEW / TOPO_INVALID_PARAMS / TOPO_INVALID_OUTPUT), nothing written.
 * Thread: pure, any thread.
 */
Diagnostics normalMap(const RasterView& dem, const NormalMapParams& params, std::uint8_t* out,
                      std::ptrdiff_t outStride);

/** @brief Encodes one unit normal (east, north, up with up >= 0). */
void encodeNormal(const std::array<double, 3>& n, NormalEncoding encoding, std::uint8_t* texel);

/**
 * @brief Decodes one texel to a unit normal (east, north, up); {0, 0, 0} for the nodata texel.
 * For tests and CPU-side lighting; shaders use the GLSL given with each encoding.
 */
std::array<float, 3> decodeNormal(const std::uint8_t* texel, NormalEncoding encoding);

}  // namespace kiosk::topo
