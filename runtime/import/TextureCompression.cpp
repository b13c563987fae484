#include "runtime/import/TextureCompression.h"

#include "runtime/core/Progress.h"
#include "runtime/import/TempStore.h"
#include "runtime/io/StoreReader.h"
#include "runtime/io/TextureBlocks.h"

#include <algorithm>
#include <astcenc.h>  // astcenc::astcenc defines ASTCENC_DYNAMIC_LIBRARY: extern "C" symbols
#include <atomic>
#include <cmath>
#include <ctime>
#include <thread>

namespace kiosk::import {

namespace {

float preset(AstcQuality q) {
    switch (q) {
        case AstcQuality::Fast:
            return ASTCENC_PRE_FAST;
        case AstcQuality::Thorough:
            return ASTCENC_PRE_THOROUGH;
        case AstcQuality::Medium:
            break;
    }
    return ASTCENC_PRE_MEDIUM;
}

double threadCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

/** One astcenc context (ASTC 4x4, LDR) for one thread; contexts are reused tile after tile. */
class AstcEncoder {
public:
    explicit AstcEncoder(AstcQuality quality) {
        astcenc_config cfg;
        if (astcenc_config_init(ASTCENC_PRF_LDR, 4, 4, 1, preset(quality), 0, &cfg) ==
            ASTCENC_SUCCESS)
            astcenc_context_alloc(&cfg, 1, &mCtx);
    }
    ~AstcEncoder() {
        if (mCtx) astcenc_context_free(mCtx);
    }
    AstcEncoder(const AstcEncoder&) = delete;
    AstcEncoder& operator=(const AstcEncoder&) = delete;
    bool valid() const noexcept { return mCtx != nullptr; }

    /** Appends the blocks of one w x h RGBA8 image to `out`. */
    bool encode(std::vector<std::uint8_t>& rgba, int w, int h, std::vector<std::uint8_t>& out) {
        void* slice = rgba.data();
        astcenc_image img{unsigned(w), unsigned(h), 1, ASTCENC_TYPE_U8, &slice};
        const std::size_t at = out.size();
        out.resize(at + io::textureImageBytes(io::TextureFormat::Astc4x4, w, h));
        const bool ok = astcenc_compress_image(mCtx, &img, &kSwizzle, out.data() + at,
                                               out.size() - at, 0) == ASTCENC_SUCCESS;
        astcenc_compress_reset(mCtx);
        return ok;
    }
    std::vector<std::uint8_t> decode(const std::uint8_t* blocks, std::size_t size, int w, int h) {
        std::vector<std::uint8_t> out(std::size_t(w) * std::size_t(h) * 4);
        void* slice = out.data();
        astcenc_image img{unsigned(w), unsigned(h), 1, ASTCENC_TYPE_U8, &slice};
        if (astcenc_decompress_image(mCtx, blocks, size, &img, &kSwizzle, 0) != ASTCENC_SUCCESS)
            out.clear();
        astcenc_decompress_reset(mCtx);
        return out;
    }

private:
    static constexpr astcenc_swizzle kSwizzle{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B,
                                              ASTCENC_SWZ_A};
    astcenc_context* mCtx = nullptr;
};

/** The next mip level: 2x2 box average (rounded), the last row/column repeated at odd sides. */
std::vector<std::uint8_t> halve(const std::vector<std::uint8_t>& src, int w, int h) {
    const int nw = std::max(1, w / 2), nh = std::max(1, h / 2);
    std::vector<std::uint8_t> out(std::size_t(nw) * std::size_t(nh) * 4);
    for (int y = 0; y < nh; ++y)
        for (int x = 0; x < nw; ++x) {
            const int x0 = std::min(2 * x, w - 1), x1 = std::min(2 * x + 1, w - 1);
            const int y0 = std::min(2 * y, h - 1), y1 = std::min(2 * y + 1, h - 1);
            for (int c = 0; c < 4; ++c) {
                auto at = [&](int px, int py) {
                    return int(src[(std::size_t(py) * std::size_t(w) + std::size_t(px)) * 4 +
                                   std::size_t(c)]);
                };
                out[(std::size_t(y) * std::size_t(nw) + std::size_t(x)) * 4 + std::size_t(c)] =
                    std::uint8_t((at(x0, y0) + at(x1, y0) + at(x0, y1) + at(x1, y1) + 2) / 4);
            }
        }
    return out;
}

/** PSNR of the colour channels (RGB); 99 dB for identical images. */
double psnrRgb(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    double se = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
        for (std::size_t c = 0; c < 3; ++c, ++n) {
            const double d = double(a[i + c]) - double(b[i + c]);
            se += d * d;
        }
    const double mse = n ? se / double(n) : 0.0;
    return mse > 0 ? std::min(99.0, 10.0 * std::log10(255.0 * 255.0 / mse)) : 99.0;
}

struct Job {
    io::ImageTile image;
    io::CompressedImage out;
    double psnr = 0;
    double cpuMs = 0;
    std::size_t rgbaBytes = 0;
    bool ok = false;
};

void encodeJob(AstcEncoder& enc, Job& j) {
    const double t0 = threadCpuMs();
    io::CompressedImage& out = j.out;
    out.id = j.image.id;
    out.format = io::TextureFormat::Astc4x4;
    out.width = j.image.width;
    out.height = j.image.height;
    out.levels = io::fullMipLevels(out.width, out.height);
    out.blocks.clear();
    std::vector<std::uint8_t> level = std::move(j.image.rgba);
    const std::vector<std::uint8_t> original = level;
    j.ok = true;
    for (int k = 0; k < out.levels && j.ok; ++k) {
        const int w = out.levelWidth(k), h = out.levelHeight(k);
        j.rgbaBytes += level.size();
        j.ok = enc.encode(level, w, h, out.blocks);
        if (k + 1 < out.levels) level = halve(level, w, h);
    }
    if (j.ok) {
        const auto back =
            enc.decode(out.blocks.data(), io::textureImageBytes(out.format, out.width, out.height),
                       out.width, out.height);
        j.ok = !back.empty();
        j.psnr = psnrRgb(original, back);
    }
    j.cpuMs = threadCpuMs() - t0;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

Result<std::vector<TextureLayerReport>> importTextureBlocks(const TextureImportOptions& o) {
    Diagnostics d;
    const std::string storePath = o.store.string();
    // Which layers: checked on the store as it is, before any copy is made.
    std::vector<std::string> layers = o.layers;
    {
        auto reader = io::StoreReader::open(o.store);
        if (!reader) return reader.diagnostics;
        const io::StoreInfo& info = (*reader.value)->info();
        if (layers.empty())
            for (const auto& l : info.layers)
                if (l.kind == io::LayerKind::Imagery) layers.push_back(l.name);
        for (const auto& name : layers) {
            const io::LayerInfo* l = info.findLayer(name);
            if (!l && info.findSequence(name))
                d.error("IMPORT_USAGE", storePath, name,
                        "is a sequence (values through a LUT): data layers are never "
                        "lossy-compressed");
            else if (!l)
                d.error("IMPORT_USAGE", storePath, name, "no such layer in the store");
            else if (l->kind != io::LayerKind::Imagery)
                d.error("IMPORT_USAGE", storePath, name,
                        "is a data layer (values through a LUT): data layers are never "
                        "lossy-compressed");
        }
        if (layers.empty())
            d.error("IMPORT_USAGE", storePath, "", "the store has no imagery layer to compress");
        if (d.hasErrors()) return d;
    }
    std::vector<TextureLayerReport> reports;
    const int threads = std::max(1, o.threads);
    Diagnostics result = withTempStore(o.store, [&](io::StoreWriter& w) -> Diagnostics {
        Diagnostics wd = w.createTileTextures();
        if (wd.hasErrors()) return wd;
        std::vector<std::unique_ptr<AstcEncoder>> encoders;
        for (int t = 0; t < threads; ++t) {
            encoders.push_back(std::make_unique<AstcEncoder>(o.quality));
            if (!encoders.back()->valid()) {
                wd.error("IMPORT_TEXTURE", storePath, "",
                         "astcenc cannot make an ASTC 4x4 context");
                return wd;
            }
        }
        Progress progress(o.quiet);
        for (const std::string& layer : layers) {
            auto ids = w.tileIds(layer);
            if (!ids) return ids.diagnostics;
            wd.append(w.deleteTileTextures(layer, io::TextureFormat::Astc4x4));
            if (wd.hasErrors()) return wd;
            TextureLayerReport report;
            report.layer = layer;
            std::vector<double> psnrs;
            progress.begin("ASTC 4x4 " + layer, std::int64_t(ids->size()));
            const std::size_t batch = std::size_t(threads) * 4;
            for (std::size_t first = 0; first < ids->size(); first += batch) {
                std::vector<Job> jobs(std::min(batch, ids->size() - first));
                for (std::size_t k = 0; k < jobs.size(); ++k) {
                    auto img = w.readImageTile(layer, (*ids)[first + k]);
                    if (!img) return img.diagnostics;
                    jobs[k].image = std::move(*img.value);
                    jobs[k].image.id = (*ids)[first + k];
                }
                std::atomic<std::size_t> next{0};
                auto work = [&](AstcEncoder& enc) {
                    for (std::size_t k = next++; k < jobs.size(); k = next++)
                        encodeJob(enc, jobs[k]);
                };
                std::vector<std::thread> pool;
                for (int t = 1; t < threads; ++t)
                    pool.emplace_back(work, std::ref(*encoders[std::size_t(t)]));
                work(*encoders[0]);
                for (auto& t : pool) t.join();
                for (Job& j : jobs) {
                    if (!j.ok) {
                        wd.error("IMPORT_TEXTURE", storePath, io::tileName(layer, j.out.id),
                                 "astcenc could not encode the tile");
                        return wd;
                    }
                    wd.append(w.putTileTexture(layer, j.out, j.psnr));
                    if (wd.hasErrors()) return wd;
                    psnrs.push_back(j.psnr);
                    report.rgbaBytes += j.rgbaBytes;
                    report.blockBytes += j.out.blocks.size();
                    report.encodeCpuMs += j.cpuMs;
                    ++report.tiles;
                }
                progress.advance(std::int64_t(jobs.size()));
            }
            progress.finish();
            report.psnrMinDb = psnrs.empty() ? 0 : *std::min_element(psnrs.begin(), psnrs.end());
            report.psnrMedianDb = median(psnrs);
            reports.push_back(report);
        }
        return wd;
    });
    if (result.hasErrors()) return result;
    return reports;
}

}  // namespace kiosk::import
