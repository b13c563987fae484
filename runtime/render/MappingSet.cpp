#include "runtime/render/MappingSet.h"

#include "runtime/core/Log.h"

#include <algorithm>
#include <cmath>

namespace kiosk::render {
namespace {

constexpr const char* kTag = "render::MappingSet";
constexpr GLuint kBlockBinding = 1;

// Bilinear resample of an RGBA float image to n x n, texel centres aligned (pixel-exact when the
// source already has that size).
std::vector<float> resample(int w, int h, const float* src, int n) {
    std::vector<float> out(std::size_t(n) * std::size_t(n) * 4);
    if (w == n && h == n) {
        std::copy(src, src + out.size(), out.begin());
        return out;
    }
    auto at = [&](int x, int y, int c) {
        x = std::clamp(x, 0, w - 1);
        y = std::clamp(y, 0, h - 1);
        return src[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4 + std::size_t(c)];
    };
    for (int y = 0; y < n; ++y) {
        const double fy = (y + 0.5) * h / n - 0.5;
        const int y0 = int(std::floor(fy));
        const float ty = float(fy - y0);
        for (int x = 0; x < n; ++x) {
            const double fx = (x + 0.5) * w / n - 0.5;
            const int x0 = int(std::floor(fx));
            const float tx = float(fx - x0);
            for (int c = 0; c < 4; ++c) {
                const float top = at(x0, y0, c) * (1 - tx) + at(x0 + 1, y0, c) * tx;
                const float bottom = at(x0, y0 + 1, c) * (1 - tx) + at(x0 + 1, y0 + 1, c) * tx;
                out[(std::size_t(y) * std::size_t(n) + std::size_t(x)) * 4 + std::size_t(c)] =
                    top * (1 - ty) + bottom * ty;
            }
        }
    }
    return out;
}

void linearClampArray() {
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

}  // namespace

glm::vec4 MappingSet::blendCoefficients(int factor) {
    switch (factor) {
        case 0:
            return {0, 0, 0, 0};  // zero
        case 1:
            return {1, 0, 0, 0};  // one
        case 2:
            return {0, 1, 0, 0};  // srcColor
        case 3:
            return {1, -1, 0, 0};  // oneMinusSrcColor
        case 4:
            return {0, 0, 1, 0};  // dstColor
        case 5:
            return {1, 0, -1, 0};  // oneMinusDstColor
        case 6:
            return {0, 0, 0, 1};  // srcAlpha
        case 7:
            return {1, 0, 0, -1};  // oneMinusSrcAlpha
        case 8:
            return {1, 0, 0, 0};  // dstAlpha: the terrain is opaque
        default:
            return {0, 0, 0, 0};  // oneMinusDstAlpha
    }
}

int MappingSet::capacityFor(int maxUniformBlockSize) {
    const int vec4s = maxUniformBlockSize / 16 - kHeaderVec4;
    return std::clamp(vec4s / kVec4PerMapping, 0, kMaxMappings);
}

Result<MappingSet> MappingSet::create(const gl::Caps& caps, int layerSize) {
    MappingSet s;
    // ES 3.0 guarantees 16 KiB blocks and 256 array layers; a context reporting 0 (not queried)
    // gets those minimums.
    const int blockSize = caps.maxUniformBlockSize > 0 ? caps.maxUniformBlockSize : 16384;
    s.mCapacity = capacityFor(blockSize);
    s.mMaxLayers = caps.maxArrayLayers > 0 ? caps.maxArrayLayers : 256;
    const int maxSize = caps.maxTextureSize > 0 ? caps.maxTextureSize : 2048;
    s.mLayerSize = std::clamp(layerSize, 2, maxSize);
    if (s.mCapacity < 1) {
        Diagnostics d;
        d.error("RENDER_MAPPING_LIMITS", "", "",
                "uniform blocks of " + std::to_string(blockSize) + " bytes hold no mapping");
        return d;
    }
    s.mBlock = gl::Buffer::create();
    glBindBuffer(GL_UNIFORM_BUFFER, s.mBlock.id());
    const auto bytes = GLsizeiptr((kHeaderVec4 + s.mCapacity * kVec4PerMapping) * 16);
    std::vector<float> zero(std::size_t(bytes / 4), 0.0f);
    glBufferData(GL_UNIFORM_BUFFER, bytes, zero.data(), GL_DYNAMIC_DRAW);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
    return s;
}

int MappingSet::addImage(int width, int height, const std::uint8_t* rgba) {
    if (int(mLayers.size()) >= mMaxLayers || width < 1 || height < 1 || !rgba) return -1;
    std::vector<float> f(std::size_t(width) * std::size_t(height) * 4);
    for (std::size_t i = 0; i < f.size(); ++i) f[i] = float(rgba[i]) / 255.0f;
    mLayers.push_back(resample(width, height, f.data(), mLayerSize));
    return int(mLayers.size()) - 1;
}

int MappingSet::addScalar(int width, int height, const float* values, double domainMin,
                          double domainMax) {
    if (int(mLayers.size()) >= mMaxLayers || width < 1 || height < 1 || !values) return -1;
    const double range = domainMax - domainMin;
    std::vector<float> f(std::size_t(width) * std::size_t(height) * 4, 0.0f);
    for (std::size_t i = 0; i < std::size_t(width) * std::size_t(height); ++i) {
        const float v = values[i];
        if (std::isnan(v)) continue;  // validity 0
        double entry;                 // texel index in the LUT row
        if (v < domainMin)
            entry = 0.0;
        else if (v > domainMax)
            entry = kLutWidth - 1;
        else
            entry = 1.0 + (range > 0 ? (v - domainMin) / range : 0.0) * (kLutEntries - 1);
        f[i * 4 + 0] = float((entry + 0.5) / kLutWidth);
        f[i * 4 + 1] = 1.0f;
    }
    mLayers.push_back(resample(width, height, f.data(), mLayerSize));
    return int(mLayers.size()) - 1;
}

int MappingSet::addLut(const std::vector<std::uint8_t>& rgba, const glm::u8vec4& below,
                       const glm::u8vec4& above) {
    if (int(mLuts.size()) >= mMaxLayers || rgba.size() < 8) return -1;
    const int n = int(rgba.size() / 4);
    std::vector<std::uint8_t> row(std::size_t(kLutWidth) * 4);
    for (int c = 0; c < 4; ++c) {
        row[std::size_t(c)] = below[c];
        row[std::size_t(kLutWidth - 1) * 4 + std::size_t(c)] = above[c];
    }
    for (int i = 0; i < kLutEntries; ++i) {
        // Entry i of 1024 from a LUT of any size: nearest by position (exact when n = 1024).
        const int src = int(std::lround(double(i) * (n - 1) / (kLutEntries - 1)));
        for (int c = 0; c < 4; ++c)
            row[std::size_t(i + 1) * 4 + std::size_t(c)] =
                rgba[std::size_t(src) * 4 + std::size_t(c)];
    }
    mLuts.push_back(std::move(row));
    return int(mLuts.size()) - 1;
}

void MappingSet::commit() {
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    mData = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D_ARRAY, mData.id());
    const int layers = std::max(1, int(mLayers.size()));
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA16F, mLayerSize, mLayerSize, layers, 0, GL_RGBA,
                 GL_FLOAT, nullptr);
    for (int i = 0; i < int(mLayers.size()); ++i)
        glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, i, mLayerSize, mLayerSize, 1, GL_RGBA,
                        GL_FLOAT, mLayers[std::size_t(i)].data());
    linearClampArray();
    mLut = gl::Texture::create();
    glBindTexture(GL_TEXTURE_2D_ARRAY, mLut.id());
    const int luts = std::max(1, int(mLuts.size()));
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, kLutWidth, 1, luts, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 nullptr);
    for (int i = 0; i < int(mLuts.size()); ++i)
        glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, i, kLutWidth, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                        mLuts[std::size_t(i)].data());
    linearClampArray();
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

bool MappingSet::setMappings(const std::vector<MappingGpu>& mappings, bool contextOn,
                             const glm::mat4& contextMatrix) {
    const std::size_t n = std::min(mappings.size(), std::size_t(mCapacity));
    const bool same = mUploadedOnce && n == mLast.size() && contextOn == mLastContext &&
                      contextMatrix == mLastContextMatrix &&
                      std::equal(mLast.begin(), mLast.end(), mappings.begin());
    if (same) return false;
    mLast.assign(mappings.begin(), mappings.begin() + std::ptrdiff_t(n));
    mLastContext = contextOn;
    mLastContextMatrix = contextMatrix;
    mUploadedOnce = true;
    std::vector<glm::vec4> block(std::size_t(kHeaderVec4 + int(n) * kVec4PerMapping));
    block[0] = glm::vec4(float(n), contextOn ? 1.0f : 0.0f, 0.0f, 0.0f);
    for (int c = 0; c < 4; ++c) block[std::size_t(1 + c)] = contextMatrix[c];
    for (std::size_t i = 0; i < n; ++i) {
        const MappingGpu& m = mappings[i];
        glm::vec4* p = &block[kHeaderVec4 + i * kVec4PerMapping];
        p[0] = m.rowS;
        p[1] = m.rowT;
        for (int c = 0; c < 3; ++c) p[2 + c] = glm::vec4(m.textureMatrix[c], 0.0f);
        for (int c = 0; c < 4; ++c) p[5 + c] = m.colorMatrix[c];
        p[9] = glm::vec4(float(m.layer), float(m.lut), m.opacity, m.focus ? 1.0f : 0.0f);
        p[10] = blendCoefficients(m.srcFactor);
        p[11] = blendCoefficients(m.dstFactor);
    }
    glBindBuffer(GL_UNIFORM_BUFFER, mBlock.id());
    glBufferSubData(GL_UNIFORM_BUFFER, 0, GLsizeiptr(block.size() * sizeof(glm::vec4)),
                    block.data());
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
    ++mBlockUploads;
    if (mappings.size() > n && !mWarnedCapacity) {
        mWarnedCapacity = true;  // one line, not one per frame
        KIOSK_LOG_WARN(kTag,
                       "%zu mappings active, the uniform block holds %d: the rest are not drawn",
                       mappings.size(), mCapacity);
    }
    return true;
}

void MappingSet::bind(GLuint program, int dataUnit, int lutUnit) const {
    glActiveTexture(GLenum(GL_TEXTURE0 + dataUnit));
    glBindTexture(GL_TEXTURE_2D_ARRAY, mData.id());
    glActiveTexture(GLenum(GL_TEXTURE0 + lutUnit));
    glBindTexture(GL_TEXTURE_2D_ARRAY, mLut.id());
    glUniform1i(glGetUniformLocation(program, "uMapData"), dataUnit);
    glUniform1i(glGetUniformLocation(program, "uMapLut"), lutUnit);
    const GLuint index = glGetUniformBlockIndex(program, "Mappings");
    if (index != GL_INVALID_INDEX) glUniformBlockBinding(program, index, kBlockBinding);
    glBindBufferBase(GL_UNIFORM_BUFFER, kBlockBinding, mBlock.id());
}

}  // namespace kiosk::render
