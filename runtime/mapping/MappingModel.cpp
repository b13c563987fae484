#include "runtime/mapping/MappingModel.h"

#include "runtime/anim/KeyedTrack.h"

#include <algorithm>
#include <cmath>

namespace kiosk::mapping {
namespace {

glm::dvec3 toVec(const config::Vec3& v) {
    return {v[0], v[1], v[2]};
}

// Direction and length interpolated apart: a symbol keyed at 0° and 90° turns at constant size
// instead of shrinking through the diagonal, as element-wise lerp would.
glm::dvec3 mixAxis(const glm::dvec3& a, const glm::dvec3& b, double t) {
    const double la = glm::length(a), lb = glm::length(b);
    if (la <= 0.0 || lb <= 0.0) return glm::mix(a, b, t);
    const glm::dvec3 da = a / la, db = b / lb;
    const double c = std::clamp(glm::dot(da, db), -1.0, 1.0);
    const double angle = std::acos(c);
    glm::dvec3 dir;
    if (angle < 1e-9 || std::abs(std::sin(angle)) < 1e-9) {
        dir = glm::mix(da, db, t);  // (anti)parallel: no unique rotation plane
    } else {
        const double s = std::sin(angle);
        dir = da * (std::sin((1.0 - t) * angle) / s) + db * (std::sin(t * angle) / s);
    }
    const double len = glm::length(dir);
    return len > 0.0 ? dir / len * glm::mix(la, lb, t) : glm::mix(a, b, t);
}

template <typename M>
M mixMatrix(const M& a, const M& b, double t) {
    M r = a;
    for (int c = 0; c < M::length(); ++c) r[c] = glm::mix(a[c], b[c], t);
    return r;
}

}  // namespace

glm::dmat3 toGlm(const config::Mat3& m) {
    glm::dmat3 r(1.0);
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) r[col][row] = m[std::size_t(row * 3 + col)];
    return r;
}

glm::dmat4 toGlm(const config::Mat4& m) {
    glm::dmat4 r(1.0);
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) r[col][row] = m[std::size_t(row * 4 + col)];
    return r;
}

MappingState evaluate(const config::ProjectiveMapping& m, double time, double clockStart) {
    MappingState s;
    s.origin = toVec(m.origin);
    s.u = toVec(m.u);
    s.v = toVec(m.v);
    s.textureMatrix = toGlm(m.textureMatrix);
    s.colorMatrix = toGlm(m.colorMatrix);
    s.opacity = m.opacity;
    s.enabled = m.enabled;
    return anim::keyedTrack(
        s, m.keys, time,
        [clockStart](const config::MappingKey& k) { return k.time.resolve(clockStart); },
        [](MappingState& k, const config::MappingKey& key) {
            // A key without a field keeps the value reached so far.
            if (key.origin) k.origin = toVec(*key.origin);
            if (key.u) k.u = toVec(*key.u);
            if (key.v) k.v = toVec(*key.v);
            if (key.textureMatrix) k.textureMatrix = toGlm(*key.textureMatrix);
            if (key.colorMatrix) k.colorMatrix = toGlm(*key.colorMatrix);
            if (key.opacity) k.opacity = *key.opacity;
        },
        [](MappingState a, const MappingState& b, double t) {
            a.origin = glm::mix(a.origin, b.origin, t);
            a.u = mixAxis(a.u, b.u, t);
            a.v = mixAxis(a.v, b.v, t);
            a.textureMatrix = mixMatrix(a.textureMatrix, b.textureMatrix, t);
            a.colorMatrix = mixMatrix(a.colorMatrix, b.colorMatrix, t);
            a.opacity = glm::mix(a.opacity, b.opacity, t);
            return a;
        });
}

glm::dvec2 TextureTransform::rect(const glm::dvec3& p) const {
    const glm::dvec4 h(p, 1.0);
    return {glm::dot(rowS, h), glm::dot(rowT, h)};
}

glm::dvec2 TextureTransform::apply(const glm::dvec3& p) const {
    const glm::dvec3 q = textureMatrix * glm::dvec3(rect(p), 1.0);
    const double iw = std::abs(q.z) > 1e-300 ? 1.0 / q.z : 0.0;
    return {q.x * iw, q.y * iw};
}

std::optional<TextureTransform> textureTransform(const MappingState& st,
                                                 const glm::dvec3& sceneOrigin) {
    const glm::dvec3 n = glm::cross(st.u, st.v);
    const double nl = glm::length(n);
    if (!(nl > 1e-12 * std::max(1.0, glm::length(st.u) * glm::length(st.v)))) return std::nullopt;
    // Columns U, V, N̂: a point P - O = a U + b V + c N̂; (a, b) in [-1/2, 1/2] on the rectangle.
    const glm::dmat3 basis(st.u, st.v, n / nl);
    const glm::dmat3 inv = glm::inverse(basis);
    const glm::dvec3 o = st.origin - sceneOrigin;
    // Rows of inv give a and b; s = a + 1/2, t = b + 1/2 (the paper's M_P scale and bias).
    const glm::dvec3 ra(inv[0][0], inv[1][0], inv[2][0]);
    const glm::dvec3 rb(inv[0][1], inv[1][1], inv[2][1]);
    TextureTransform t;
    t.rowS = glm::dvec4(ra, 0.5 - glm::dot(ra, o));
    t.rowT = glm::dvec4(rb, 0.5 - glm::dot(rb, o));
    t.textureMatrix = st.textureMatrix;
    return t;
}

}  // namespace kiosk::mapping
