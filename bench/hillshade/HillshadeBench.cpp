// Hillshade throughput of kiosk::topo against `gdaldem hillshade` on the same synthetic
// Float32 GeoTIFFs, measured in the same run. Prints ONE JSON object on stdout.
//
//   hillshade_bench [--with-16k] [--sizes 4096,8192] [--tmp DIR]
//
// Default: 4096 x 4096 only (about 20 s). --with-16k adds 16384 x 16384 (1 GiB of floats,
// several minutes, needs ~3 GiB RAM and ~1.3 GiB in the temp dir).
// Figures: ours_compute_* time the hillshade on an in-memory DEM (what the importer does per
// tile, the DEM already read); ours_end_to_end_2t adds reading the GeoTIFF with GDAL and
// writing a Byte GeoTIFF, which is what gdaldem's wall time includes. gdaldem is
// single-threaded; ours splits rows across 2 threads.

#include "runtime/topo/Hillshade.h"
#include "runtime/topo/NormalMap.h"
#include "runtime/topo/Shadow.h"

#include <cpl_conv.h>
#include <gdal_priv.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
using kiosk::topo::HillshadeParams;
using kiosk::topo::RasterView;

constexpr double kPixel = 30.0;

double seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

// Mountains: a few octaves of smooth waves plus hashed noise, ~0..3000 m.
std::vector<float> makeDem(int n) {
    std::vector<float> dem(static_cast<std::size_t>(n) * n);
    for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c) {
            const double x = c * kPixel;
            const double y = r * kPixel;
            double h = 1500.0;
            double amp = 700.0;
            double freq = 1.0 / 9000.0;
            for (int o = 0; o < 5; ++o) {
                h += amp * std::sin(x * freq + o * 1.3) * std::cos(y * freq * 1.1 + o * 0.7);
                amp *= 0.45;
                freq *= 2.3;
            }
            unsigned hash =
                static_cast<unsigned>(c) * 73856093u ^ static_cast<unsigned>(r) * 19349663u;
            hash ^= hash >> 13;
            hash *= 0x5bd1e995u;
            h += static_cast<double>(hash & 0xff) / 255.0 * 4.0;
            dem[static_cast<std::size_t>(r) * n + c] = static_cast<float>(h);
        }
    }
    return dem;
}

bool writeTiff(const std::string& path, const void* data, int n, GDALDataType type) {
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    const char* options[] = {"TILED=YES", nullptr};
    GDALDataset* ds = drv->Create(path.c_str(), n, n, 1, type, const_cast<char**>(options));
    if (ds == nullptr) return false;
    double gt[6] = {500000.0, kPixel, 0.0, 5000000.0, 0.0, -kPixel};
    ds->SetGeoTransform(gt);
    const CPLErr err = ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, n, n, const_cast<void*>(data),
                                                      n, n, type, 0, 0);
    GDALClose(ds);
    return err == CE_None;
}

bool readFloat(const std::string& path, std::vector<float>& out, int n) {
    auto* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly));
    if (ds == nullptr) return false;
    out.resize(static_cast<std::size_t>(n) * n);
    const CPLErr err =
        ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, n, n, out.data(), n, n, GDT_Float32, 0, 0);
    GDALClose(ds);
    return err == CE_None;
}

// Rows split into `threads` bands; each band is a view with a 1-pixel apron into the same DEM.
template <class Fn>
void parallelRows(int n, int threads, Fn fn) {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) {
        const int y0 = n * t / threads;
        const int y1 = n * (t + 1) / threads;
        pool.emplace_back([=] { fn(y0, y1); });
    }
    for (auto& th : pool) th.join();
}

double hillshadeRun(const std::vector<float>& dem, std::vector<std::uint8_t>& out, int n,
                    int threads, const HillshadeParams& p) {
    const auto t0 = Clock::now();
    parallelRows(n, threads, [&](int y0, int y1) {
        const RasterView v =
            RasterView::window(dem.data(), n, n, n, 0, y0, n, y1 - y0, kPixel, kPixel, 1);
        const auto d =
            kiosk::topo::hillshade(v, p, out.data() + static_cast<std::size_t>(y0) * n, n);
        if (d.hasErrors()) std::fprintf(stderr, "%s\n", d.format().c_str());
    });
    return seconds(t0, Clock::now());
}

double shadowRun(const std::vector<float>& dem, std::vector<std::uint8_t>& mask, int n, int threads,
                 const HillshadeParams& p) {
    const auto t0 = Clock::now();
    // Each band reads only the apron a ray can need (what the importer does per tile).
    const auto [lo, hi] = std::minmax_element(dem.begin(), dem.end());
    const int apron = kiosk::topo::requiredShadowApron(*hi - *lo, p, kPixel, kPixel);
    parallelRows(n, threads, [&](int y0, int y1) {
        const RasterView v =
            RasterView::window(dem.data(), n, n, n, 0, y0, n, y1 - y0, kPixel, kPixel, apron);
        const auto d =
            kiosk::topo::castShadows(v, p, mask.data() + static_cast<std::size_t>(y0) * n, n);
        if (d.hasErrors()) std::fprintf(stderr, "%s\n", d.format().c_str());
    });
    return seconds(t0, Clock::now());
}

// Normal map (Rgb8, 3 bytes per pixel) of the same DEM: the importer's --normals work per pixel.
double normalMapRun(const std::vector<float>& dem, std::vector<std::uint8_t>& out, int n,
                    int threads) {
    const auto t0 = Clock::now();
    parallelRows(n, threads, [&](int y0, int y1) {
        const RasterView v =
            RasterView::window(dem.data(), n, n, n, 0, y0, n, y1 - y0, kPixel, kPixel, 1);
        const auto d = kiosk::topo::normalMap(v, kiosk::topo::NormalMapParams{},
                                              out.data() + static_cast<std::size_t>(y0) * n * 3,
                                              static_cast<std::ptrdiff_t>(n) * 3);
        if (d.hasErrors()) std::fprintf(stderr, "%s\n", d.format().c_str());
    });
    return seconds(t0, Clock::now());
}

struct Run {
    int size = 0;
    double ours1 = 0, ours2 = 0, oursE2E = 0, gdal = 0, shadows2 = 0, normals2 = 0;
    int maxDiff = -1;
    long long beyondOne = -1;
    bool ok = false;
    std::string error;
};

Run benchSize(int n, const std::string& dir, int repeats) {
    Run run;
    run.size = n;
    const std::string src = dir + "/dem_" + std::to_string(n) + ".tif";
    const std::string gdalOut = dir + "/gdal_" + std::to_string(n) + ".tif";
    const std::string ourOut = dir + "/ours_" + std::to_string(n) + ".tif";
    std::vector<float> dem = makeDem(n);
    if (!writeTiff(src, dem.data(), n, GDT_Float32)) {
        run.error = "cannot write " + src;
        return run;
    }
    HillshadeParams p;  // gdaldem defaults: Horn, 315/45, z 1, s 1, no -compute_edges
    std::vector<std::uint8_t> out(static_cast<std::size_t>(n) * n);
    const double mp = static_cast<double>(n) * n / 1e6;
    double best1 = 1e30, best2 = 1e30, bestE2E = 1e30, bestGdal = 1e30;
    for (int i = 0; i < repeats; ++i) {
        best1 = std::min(best1, hillshadeRun(dem, out, n, 1, p));
        best2 = std::min(best2, hillshadeRun(dem, out, n, 2, p));

        const auto t0 = Clock::now();
        std::vector<float> read;
        if (!readFloat(src, read, n)) {
            run.error = "cannot read " + src;
            return run;
        }
        hillshadeRun(read, out, n, 2, p);
        if (!writeTiff(ourOut, out.data(), n, GDT_Byte)) {
            run.error = "cannot write " + ourOut;
            return run;
        }
        bestE2E = std::min(bestE2E, seconds(t0, Clock::now()));

        const std::string cmd = "GDAL_PAM_ENABLED=NO gdaldem hillshade -q '" + src + "' '" +
                                gdalOut + "' >/dev/null 2>&1";
        const auto g0 = Clock::now();
        if (std::system(cmd.c_str()) != 0) {
            run.error = "gdaldem failed (is gdal-bin installed?)";
            return run;
        }
        bestGdal = std::min(bestGdal, seconds(g0, Clock::now()));
    }
    // Same answer as gdaldem, or the speed comparison is meaningless.
    {
        auto* ds = static_cast<GDALDataset*>(GDALOpen(gdalOut.c_str(), GA_ReadOnly));
        std::vector<std::uint8_t> ref(out.size());
        if (ds == nullptr || ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, n, n, ref.data(), n, n,
                                                            GDT_Byte, 0, 0) != CE_None) {
            run.error = "cannot read gdaldem output";
            if (ds) GDALClose(ds);
            return run;
        }
        GDALClose(ds);
        run.maxDiff = 0;
        run.beyondOne = 0;
        for (std::size_t i = 0; i < ref.size(); ++i) {
            const int d = std::abs(int(ref[i]) - int(out[i]));
            run.maxDiff = std::max(run.maxDiff, d);
            run.beyondOne += d > 1;
        }
    }
    {
        std::vector<std::uint8_t> mask(out.size());
        HillshadeParams light;
        light.altitudeDeg = 30.0;
        run.shadows2 = mp / shadowRun(dem, mask, n, 2, light);
    }
    {
        std::vector<std::uint8_t> normals(out.size() * 3);
        double best = 1e30;
        for (int k = 0; k < (n > 8192 ? 1 : 3); ++k) best = std::min(best, normalMapRun(dem, normals, n, 2));
        run.normals2 = mp / best;
    }
    run.ours1 = mp / best1;
    run.ours2 = mp / best2;
    run.oursE2E = mp / bestE2E;
    run.gdal = mp / bestGdal;
    run.ok = true;
    std::error_code ec;
    std::filesystem::remove(src, ec);
    std::filesystem::remove(gdalOut, ec);
    std::filesystem::remove(ourOut, ec);
    return run;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<int> sizes{4096};
    std::string tmp = std::filesystem::temp_directory_path().string();
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--with-16k") {
            sizes.push_back(16384);
        } else if (a == "--tmp" && i + 1 < argc) {
            tmp = argv[++i];
        } else if (a == "--sizes" && i + 1 < argc) {
            sizes.clear();
            std::string list = argv[++i];
            for (std::size_t s = 0; s < list.size();) {
                const std::size_t e = std::min(list.find(',', s), list.size());
                sizes.push_back(std::atoi(list.substr(s, e - s).c_str()));
                s = e + 1;
            }
        } else {
            std::fprintf(stderr, "usage: %s [--with-16k] [--sizes N,M] [--tmp DIR]\n", argv[0]);
            return 2;
        }
    }
    CPLSetConfigOption("GDAL_PAM_ENABLED", "NO");
    GDALAllRegister();
    const std::string dir = tmp + "/kiosk-hillshade-bench-" + std::to_string(::getpid());
    std::filesystem::create_directories(dir);

    std::string json =
        "{\"benchmark\":\"hillshade\",\"algorithm\":\"Horn 315/45 default\","
        "\"threads_ours\":2,\"baseline\":\"gdaldem hillshade (" +
        std::string(GDALVersionInfo("RELEASE_NAME")) +
        ", single-threaded, wall time incl. GeoTIFF read+write)\",\"runs\":[";
    bool first = true;
    bool allOk = true;
    for (int n : sizes) {
        if (n < 16) continue;
        const Run r = benchSize(n, dir, n > 8192 ? 1 : 3);
        allOk = allOk && r.ok;
        char buf[1024];
        if (!r.ok) {
            std::snprintf(buf, sizeof buf, "%s{\"size\":%d,\"error\":\"%s\"}", first ? "" : ",", n,
                          r.error.c_str());
        } else {
            std::snprintf(buf, sizeof buf,
                          "%s{\"size\":%d,\"megapixels\":%.2f,\"ours_compute_1t_mps\":%.1f,"
                          "\"ours_compute_2t_mps\":%.1f,\"ours_end_to_end_2t_mps\":%.1f,"
                          "\"gdaldem_mps\":%.1f,\"ratio_compute_2t_vs_gdaldem\":%.2f,"
                          "\"ratio_end_to_end_vs_gdaldem\":%.2f,\"shadows_alt30_2t_mps\":%.1f,"
                          "\"max_abs_diff_vs_gdaldem\":%d,\"pixels_beyond_1dn\":%lld,"
                          "\"normal_map_rgb8_2t_mps\":%.1f,\"ratio_normal_map_vs_gdaldem_hillshade\":%.2f}",
                          first ? "" : ",", n, double(n) * n / 1e6, r.ours1, r.ours2, r.oursE2E,
                          r.gdal, r.ours2 / r.gdal, r.oursE2E / r.gdal, r.shadows2, r.maxDiff,
                          r.beyondOne, r.normals2, r.normals2 / r.gdal);
        }
        json += buf;
        first = false;
    }
    // Other processes share the 2 cores of the build machine: say how busy it was.
    double load = -1.0;
    if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
        if (std::fscanf(f, "%lf", &load) != 1) load = -1.0;
        std::fclose(f);
    }
    char tail[128];
    std::snprintf(tail, sizeof tail, "],\"hardware_threads\":%u,\"loadavg_1min_at_end\":%.2f}",
                  std::thread::hardware_concurrency(), load);
    json += tail;
    std::printf("%s\n", json.c_str());
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    return allOk ? 0 : 1;
}
