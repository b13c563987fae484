#include "runtime/topo/NormalMap.h"

#include "runtime/topo/Gradient.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace kiosk::topo {

namespace {

inline std::uint8_t unitToByte(double v) {  // [-1, 1] -> [0, 255], rounded
    const double b = (v * 0.5 + 0.5) * 255.0 + 0.5;
    return static_cast<std::uint8_t>(b <= 0.0 ? 0.0 : (b >= 255.0 ? 255.0 : b));
}

inline float byteToUnit(std::uint8_t b) {
    return static_cast<float>(b) / 255.0f * 2.0f - 1.0f;
}

}  // namespace

int bytesPerTexel(NormalEncoding encoding) {
    return encoding == NormalEncoding::Rgb8 ? 3 : 2;
}

void encodeNormal(const std::array<double, 3>& n, NormalEncoding encoding, std::uint8_t* texel) {
    if (encoding == NormalEncoding::Rgb8) {
        texel[0] = unitToByte(n[0]);
        texel[1] = unitToByte(n[1]);
        // A (nearly) horizontal normal would encode blue as 127/128; never let a valid texel
        // collide with the nodata value (0, 0, 0).
        texel[2] = std::max<std::uint8_t>(unitToByte(n[2]), 128);
        return;
    }
    const double l1 = std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]);
    const double px = l1 > 0.0 ? n[0] / l1 : 0.0;
    const double py = l1 > 0.0 ? n[1] / l1 : 0.0;
    // Rotating the diamond |px| + |py| <= 1 by 45 degrees fills the whole byte square: sqrt(2)
    // finer steps than storing px, py (8-bit px, py alone miss the 2 DN lighting budget).
    // Of the four codes around (q * 0.5 + 0.5) * 255, keep the one that decodes closest to n
    // (Cigolle et al. 2014, "precise" octahedral encoding): rounding each channel on its own
    // is up to ~2.1 DN off in Lambert lighting, the best neighbour stays within 2.
    const double fu = std::clamp(((px + py) * 0.5 + 0.5) * 255.0, 0.0, 255.0);
    const double fv = std::clamp(((px - py) * 0.5 + 0.5) * 255.0, 0.0, 255.0);
    double best = -2.0;
    for (const double cu : {std::floor(fu), std::ceil(fu)})
        for (const double cv : {std::floor(fv), std::ceil(fv)}) {
            const std::uint8_t candidate[2] = {static_cast<std::uint8_t>(cu),
                                               static_cast<std::uint8_t>(cv)};
            const auto d = decodeNormal(candidate, NormalEncoding::Octahedral8);
            const double cosAngle = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
            if (cosAngle > best) {
                best = cosAngle;
                texel[0] = candidate[0];
                texel[1] = candidate[1];
            }
        }
    // (0, 0) is the horizontal west normal, reachable only by rounding an extreme slope;
    // keep it for nodata.
    if (texel[0] == 0 && texel[1] == 0) texel[1] = 1;
}

std::array<float, 3> decodeNormal(const std::uint8_t* texel, NormalEncoding encoding) {
    float n[3];
    if (encoding == NormalEncoding::Rgb8) {
        if (texel[0] == 0 && texel[1] == 0 && texel[2] == 0) return {0.0f, 0.0f, 0.0f};
        n[0] = byteToUnit(texel[0]);
        n[1] = byteToUnit(texel[1]);
        n[2] = byteToUnit(texel[2]);
    } else {
        if (texel[0] == 0 && texel[1] == 0) return {0.0f, 0.0f, 0.0f};
        const float u = byteToUnit(texel[0]);
        const float v = byteToUnit(texel[1]);
        n[0] = 0.5f * (u + v);
        n[1] = 0.5f * (u - v);
        n[2] = std::max(0.0f, 1.0f - std::abs(n[0]) - std::abs(n[1]));
    }
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0.0f)) return {0.0f, 0.0f, 1.0f};
    return {n[0] / len, n[1] / len, n[2] / len};
}

Diagnostics normalMap(const RasterView& dem, const NormalMapParams& params, std::uint8_t* out,
                      std::ptrdiff_t outStride) {
    HillshadeParams g;
    g.zFactor = params.zFactor;
    g.scale = params.scale;
    g.algorithm = params.algorithm;
    g.computeEdges = params.computeEdges;
    Diagnostics d = dem.validate("normalMap");
    d.append(validateParams(g, "normalMap"));
    const int bpt = bytesPerTexel(params.encoding);
    if (out == nullptr)
        d.error("TOPO_INVALID_OUTPUT", "", "normalMap", "output buffer is null");
    else if (dem.width > 0 && outStride < static_cast<std::ptrdiff_t>(dem.width) * bpt)
        d.error("TOPO_INVALID_OUTPUT", "", "normalMap",
                "output stride " + std::to_string(outStride) + " is smaller than width * " +
                    std::to_string(bpt) +
                    " bytes = " + std::to_string(static_cast<long long>(dem.width) * bpt));
    if (d.hasErrors()) return d;

    const double zs = detail::gradientScale(g);
    detail::GradientRows rows(dem, params.algorithm, params.computeEdges);
    for (int r = 0; r < dem.height; ++r) {
        rows.compute(r);
        const float* gx = rows.x();
        const float* gy = rows.y();
        const std::uint8_t* ok = rows.valid();
        std::uint8_t* texel = out + r * outStride;
        for (int c = 0; c < dem.width; ++c, texel += bpt) {
            if (!ok[c]) {
                for (int i = 0; i < bpt; ++i) texel[i] = 0;
                continue;
            }
            // gx = -dz/dEast / zs, gy = dz/dNorth / zs (see Gradient.h).
            const double e = zs * gx[c];
            const double n = -zs * gy[c];
            const double inv = 1.0 / std::sqrt(e * e + n * n + 1.0);
            encodeNormal({e * inv, n * inv, inv}, params.encoding, texel);
        }
    }
    return d;
}

}  // namespace kiosk::topo
