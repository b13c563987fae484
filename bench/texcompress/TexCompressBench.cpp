// GPU texture compression measurement (issue 20, W04 §4; docs/terrain.md §11): the store's
// imagery tiles encoded as ASTC 4x4 with Debian's astcenc (the only well-kept ASTC/ETC2 encoder
// Debian 12 packages; there is no ETC2 encoder), their colour error (PSNR per layer), encode
// cost, and what llvmpipe does with compressed uploads: the bytes it holds per texture (resident
// set growth over many uploads), upload time and the frame time of a full-screen pass sampling
// them, against RGBA8 in the same run. With --scenario and --compressed (a copy of the
// scenario's store after `geokiosk import textures`): the running scene with the stored ASTC
// blocks uploaded (terrain.textureCompression "astc") against the PNG tiles ("off"), the same
// store, two sessions side by side, passes alternating: GPU texture bytes, time to settle a
// view from cold (loads + uploads), frame time. Prints ONE JSON object.
//
// usage: bench-texcompress STORE [--tiles N] [--copies N]
//                          [--scenario SCENARIO --compressed STORE [--frames N] [--passes N]]
#include <GLES3/gl3.h>

#include <sys/resource.h>
#include <unistd.h>
// After gl3.h: the KHR ASTC enums.
#include "runtime/app/FrameStats.h"
#include "runtime/app/Session.h"
#include "runtime/core/Clock.h"
#include "runtime/gl/ProgramBuilder.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/io/StoreReader.h"

#include "bench/common/BenchArgs.h"
#include "bench/common/HeadlessGl.h"
#include <GLES2/gl2ext.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <astcenc.h>  // astcenc::astcenc defines ASTCENC_DYNAMIC_LIBRARY: extern "C" symbols
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

using namespace kiosk;

namespace {

double threadCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

/** ASTC 4x4 LDR encoder/decoder for one tile size (astcenc contexts are reusable). */
struct Astc {
    astcenc_context* ctx = nullptr;
    astcenc_swizzle swz{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
    explicit Astc(float preset) {
        astcenc_config cfg;
        if (astcenc_config_init(ASTCENC_PRF_LDR, 4, 4, 1, preset, 0, &cfg) == ASTCENC_SUCCESS)
            astcenc_context_alloc(&cfg, 1, &ctx);
    }
    ~Astc() {
        if (ctx) astcenc_context_free(ctx);
    }
    Astc(const Astc&) = delete;
    Astc& operator=(const Astc&) = delete;
    std::vector<std::uint8_t> encode(std::vector<std::uint8_t>& rgba, int w, int h) {
        void* slice = rgba.data();
        astcenc_image img{unsigned(w), unsigned(h), 1, ASTCENC_TYPE_U8, &slice};
        std::vector<std::uint8_t> blocks(std::size_t((w + 3) / 4) * std::size_t((h + 3) / 4) * 16);
        const bool ok = astcenc_compress_image(ctx, &img, &swz, blocks.data(), blocks.size(), 0) ==
                        ASTCENC_SUCCESS;
        astcenc_compress_reset(ctx);
        return ok ? blocks : std::vector<std::uint8_t>{};
    }
    std::vector<std::uint8_t> decode(std::vector<std::uint8_t>& blocks, int w, int h) {
        std::vector<std::uint8_t> out(std::size_t(w) * std::size_t(h) * 4);
        void* slice = out.data();
        astcenc_image img{unsigned(w), unsigned(h), 1, ASTCENC_TYPE_U8, &slice};
        astcenc_decompress_image(ctx, blocks.data(), blocks.size(), &img, &swz, 0);
        astcenc_decompress_reset(ctx);
        return out;
    }
};

/** PSNR over the colour channels (alpha is opaque in imagery tiles). */
double psnr(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    double se = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
        for (int c = 0; c < 3; ++c, ++n) {
            const double d = double(a[i + std::size_t(c)]) - double(b[i + std::size_t(c)]);
            se += d * d;
        }
    const double mse = n ? se / double(n) : 0.0;
    return mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : 99.0;
}

/** Resident growth (KiB per texture) and upload ms per texture over `copies` uploads. */
struct UploadCost {
    double kibPerTexture = 0, msPerUpload = 0;
    std::vector<gl::Texture> textures;
};
template <class Upload>
UploadCost uploads(int copies, Upload upload) {
    UploadCost c;
    glFinish();
    const double r0 = bench::currentRssMb();
    RealClock clock;
    const double t0 = clock.now();
    for (int i = 0; i < copies; ++i) {
        c.textures.push_back(gl::Texture::create());
        glBindTexture(GL_TEXTURE_2D, c.textures.back().id());
        upload();
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    }
    glFinish();
    c.msPerUpload = (clock.now() - t0) * 1000.0 / copies;
    c.kibPerTexture = (bench::currentRssMb() - r0) * 1024.0 / copies;
    return c;
}

/** Frame ms of a full-screen pass doing 4 dependent fetches of `tex` per pixel. */
double sampleMs(GLuint program, GLuint tex, GLuint vao, int frames) {
    std::vector<double> ms;
    RealClock clock;
    glUseProgram(program);
    glDisable(GL_DEPTH_TEST);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex);
    glUniform1i(glGetUniformLocation(program, "uTex"), 0);
    glBindVertexArray(vao);
    for (int i = 0; i < frames; ++i) {
        glFinish();
        const double t0 = clock.now();
        glDrawArrays(GL_TRIANGLES, 0, 6);
        glFinish();
        ms.push_back((clock.now() - t0) * 1000.0);
    }
    return app::percentile(ms, 50);
}

/** One mode of the running-scene comparison. */
struct SceneMode {
    std::unique_ptr<app::Session> session;
    std::vector<double> frameMs;
    double settleMs = 0, uploadMs = 0;
    scene::SceneCacheUsage usage;
};

/** The scenario's views drawn with the stored ASTC blocks and with the PNG tiles (same store). */
nlohmann::json sceneComparison(const bench::HeadlessGl& gl, const std::string& scenario,
                               const std::string& store, int frames, int passes) {
    nlohmann::json out;
    const int w = 1280, h = 720;
    auto target = gl::RenderTarget::create(w, h);
    if (!target) return {{"error", "no render target"}};
    target->bind();
    SceneMode modes[2];
    const config::TextureCompression kinds[2] = {config::TextureCompression::Off,
                                                 config::TextureCompression::Astc};
    for (int m = 0; m < 2; ++m) {
        auto s = app::Session::open(scenario, gl.caps, [&](config::Scenario& sc) {
            for (auto& [id, ref] : sc.stores)
                if (id == sc.terrain.store) ref.path = store;
            sc.terrain.textureCompression = kinds[m];
        });
        if (!s) return {{"error", s.diagnostics.format()}};
        modes[m].session = std::move(*s.value);
    }
    out["texture_format"] = {
        {"off", io::textureFormatName(modes[0].session->terrain().textureChoice().format)},
        {"astc", io::textureFormatName(modes[1].session->terrain().textureChoice().format)}};
    RealClock clock;
    for (const auto& [name, vp] : modes[0].session->scenario().viewpoints) {
        (void)vp;
        nlohmann::json v;
        v["viewpoint"] = name;
        for (SceneMode& m : modes) {
            m.frameMs.clear();
            m.uploadMs = 0;
            app::Session& s = *m.session;
            auto at = s.viewpointAt(s.startTime(), name);
            if (!at) continue;
            const math::Camera cam =
                app::makeCamera(*at, s.terrain().bounds(), w, h, s.scenario().camera.fovY);
            // From what is resident after the previous view: loads and uploads of this one.
            const double t0 = clock.now();
            for (int k = 0; k < 60000 && (k == 0 || !s.terrain().settled()); ++k) {
                s.prepare(cam, s.startTime());
                m.uploadMs += s.terrain().frameInfo().uploadMs;
            }
            m.settleMs = (clock.now() - t0) * 1000.0;
            m.usage = s.terrain().cacheUsage();
        }
        for (int p = 0; p < passes; ++p)
            for (SceneMode& m : modes) {
                app::Session& s = *m.session;
                auto at = s.viewpointAt(s.startTime(), name);
                if (!at) continue;
                const math::Camera cam =
                    app::makeCamera(*at, s.terrain().bounds(), w, h, s.scenario().camera.fovY);
                for (int i = 0; i < frames; ++i) {
                    const double t0 = clock.now();
                    s.drawFrame(cam, s.startTime(), w, h);
                    glFinish();
                    m.frameMs.push_back((clock.now() - t0) * 1000.0);
                }
            }
        const char* names[2] = {"off_baseline", "astc"};
        for (int k = 0; k < 2; ++k) {
            const SceneMode& m = modes[k];
            if (m.frameMs.empty()) continue;
            v[names[k]] = {{"frame_ms_p50", app::percentile(m.frameMs, 50)},
                           {"frame_ms_min", *std::min_element(m.frameMs.begin(), m.frameMs.end())},
                           {"settle_ms", m.settleMs},
                           {"upload_ms_while_settling", m.uploadMs},
                           {"gpu_texture_bytes", m.usage.gpuTextures},
                           {"gpu_texture_bytes_compressed", m.usage.gpuTexturesCompressed}};
        }
        out["views"].push_back(v);
    }
    out["size"] = "1280x720";
    out["frames_per_pass"] = frames;
    out["passes"] = passes;
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench-texcompress STORE [--tiles N] [--copies N]\n");
        return 2;
    }
    int maxTiles = 12, copies = 64, frames = 5, passes = 4;
    std::string scenario, compressed;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--tiles"))
            maxTiles = std::max(1, std::atoi(argv[i + 1]));
        else if (!std::strcmp(argv[i], "--copies"))
            copies = std::max(4, std::atoi(argv[i + 1]));
        else if (!std::strcmp(argv[i], "--scenario"))
            scenario = argv[i + 1];
        else if (!std::strcmp(argv[i], "--compressed"))
            compressed = argv[i + 1];
        else if (!std::strcmp(argv[i], "--frames"))
            frames = std::max(1, std::atoi(argv[i + 1]));
        else if (!std::strcmp(argv[i], "--passes"))
            passes = std::max(1, std::atoi(argv[i + 1]));
        else
            return 2;
    }
    if (scenario.empty() != compressed.empty()) {
        std::fprintf(stderr, "bench-texcompress: --scenario and --compressed go together\n");
        return 2;
    }
    auto headless = bench::openHeadlessGl();
    if (!headless) return 3;
    auto reader = io::StoreReader::open(argv[1]);
    if (!reader) {
        std::fprintf(stderr, "%s", reader.diagnostics.format().c_str());
        return 1;
    }
    io::StoreReader& store = **reader;
    const bool astcExposed = headless->caps.hasExtension("GL_KHR_texture_compression_astc_ldr");
    nlohmann::json out;
    out["benchmark"] = "texture_compression";
    out["store"] = argv[1];
    out["renderer"] = headless->caps.renderer;
    out["astc_ldr_exposed"] = astcExposed;
    out["etc2_encoder"] =
        "none packaged in Debian 12 (ETC2/EAC measured with valid constant blocks)";
    Astc astc(ASTCENC_PRE_FAST);
    if (!astc.ctx) return 3;
    std::vector<std::uint8_t> sampleRgba, sampleBlocks;
    int sampleW = 0, sampleH = 0;
    for (const io::LayerInfo& layer : store.info().layers) {
        if (layer.kind != io::LayerKind::Imagery) continue;
        std::vector<double> psnrs, encodeCpuMs;
        std::size_t rawBytes = 0, astcBytes = 0;
        int tiles = 0;
        for (int level = layer.levels - 1; level >= 0 && tiles < maxTiles; --level) {
            const auto& m = store.info().grid.levels[std::size_t(level)];
            for (int row = 0; row < m.matrixHeight && tiles < maxTiles; ++row)
                for (int col = 0; col < m.matrixWidth && tiles < maxTiles; ++col) {
                    auto img = store.readImagery(layer.name, TileId{level, col, row});
                    if (!img || img->width % 4 || img->height % 4) continue;
                    const double c0 = threadCpuMs();
                    auto blocks = astc.encode(img->rgba, img->width, img->height);
                    encodeCpuMs.push_back(threadCpuMs() - c0);
                    if (blocks.empty()) continue;
                    psnrs.push_back(psnr(img->rgba, astc.decode(blocks, img->width, img->height)));
                    rawBytes += img->rgba.size();
                    astcBytes += blocks.size();
                    if (sampleBlocks.empty()) {
                        sampleRgba = img->rgba, sampleBlocks = blocks;
                        sampleW = img->width, sampleH = img->height;
                    }
                    ++tiles;
                }
        }
        if (psnrs.empty()) continue;
        out["layers"].push_back(
            {{"layer", layer.name},
             {"tiles", tiles},
             {"astc4x4_psnr_db_min", *std::min_element(psnrs.begin(), psnrs.end())},
             {"astc4x4_psnr_db_median", app::percentile(psnrs, 50)},
             {"encode_cpu_ms_per_tile_median", app::percentile(encodeCpuMs, 50)},
             {"rgba8_bytes", rawBytes},
             {"astc4x4_bytes", astcBytes}});
    }
    if (sampleBlocks.empty()) {
        out["skipped"] = "no imagery tile in the store";
        std::printf("%s\n", out.dump().c_str());
        return 0;
    }
    // What llvmpipe holds and costs per texture (level 0 only, the same tile each time).
    const std::vector<std::uint8_t> etc2(sampleBlocks.size(), 0);
    UploadCost rgba = uploads(copies, [&] {
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, sampleW, sampleH, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                     sampleRgba.data());
    });
    UploadCost astcUp = uploads(copies, [&] {
        glCompressedTexImage2D(GL_TEXTURE_2D, 0, GL_COMPRESSED_RGBA_ASTC_4x4_KHR, sampleW, sampleH,
                               0, GLsizei(sampleBlocks.size()), sampleBlocks.data());
    });
    UploadCost etcUp = uploads(copies, [&] {
        glCompressedTexImage2D(GL_TEXTURE_2D, 0, GL_COMPRESSED_RGBA8_ETC2_EAC, sampleW, sampleH, 0,
                               GLsizei(etc2.size()), etc2.data());
    });
    out["gl_error"] = glGetError();
    out["tile"] = std::to_string(sampleW) + "x" + std::to_string(sampleH);
    out["copies"] = copies;
    out["llvmpipe_resident_kib_per_texture"] = {{"rgba8", rgba.kibPerTexture},
                                                {"astc4x4", astcUp.kibPerTexture},
                                                {"etc2_eac", etcUp.kibPerTexture}};
    out["upload_ms_per_texture"] = {{"rgba8", rgba.msPerUpload},
                                    {"astc4x4", astcUp.msPerUpload},
                                    {"etc2_eac", etcUp.msPerUpload}};
    out["data_bytes_per_texture"] = {{"rgba8", sampleRgba.size()},
                                     {"astc4x4", sampleBlocks.size()}};
    auto target = gl::RenderTarget::create(1280, 720);
    auto program = gl::buildProgram("fillbound.vert", "fillbound.frag", {"FETCHES 4"});
    if (target && program) {
        target->bind();
        gl::VertexArray vao = gl::VertexArray::create();
        const GLuint p = program->id();
        const double a = sampleMs(p, rgba.textures.front().id(), vao.id(), 15);
        const double b = sampleMs(p, astcUp.textures.front().id(), vao.id(), 15);
        const double c = sampleMs(p, rgba.textures.front().id(), vao.id(), 15);
        out["full_screen_4_fetch_ms_p50"] = {{"rgba8", std::min(a, c)}, {"astc4x4", b}};
    }
    if (!scenario.empty())
        out["scene"] = sceneComparison(*headless, scenario, compressed, frames, passes);
    std::printf("%s\n", out.dump().c_str());
    return 0;
}
