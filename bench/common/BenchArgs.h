#pragma once
// Small helpers the C++ benchmarks share: views and options given on the command line, the
// process's resident set now.
#include "runtime/core/Strings.h"
#include "runtime/math/Camera.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

namespace kiosk::bench {

/** @brief "X,Y,Z,HEADING,PITCH,RANGE" (world metres, degrees) as a viewpoint; false if not. */
inline bool parseViewpoint(const std::string& text, math::Viewpoint& vp) {
    double v[6];
    const char* p = text.c_str();
    for (int i = 0; i < 6; ++i) {
        char* end = nullptr;
        v[i] = std::strtod(p, &end);
        if (end == p || (i < 5 && *end != ',') || (i == 5 && *end)) return false;
        p = end + 1;
    }
    vp = {glm::dvec3(v[0], v[1], v[2]), v[3], v[4], v[5]};
    return true;
}

/** @brief The options of the benchmarks that time views of one scenario. */
struct ViewBenchArgs {
    std::string scenario;
    std::vector<math::Viewpoint> views;  ///< --view X,Y,Z,HEADING,PITCH,RANGE (repeatable)
    int width = 1280, height = 720;      ///< --size WxH
    int frames = 5;                      ///< --frames N per pass
    int passes = 4;                      ///< --passes N
};

/**
 * @brief Parse `SCENARIO [--view ...]... [--size WxH] [--frames N] [--passes N]`, handing any
 * other option (name, value) to `extra` (false: not understood). Prints what is wrong and
 * returns false on a usage error (exit 2).
 */
inline bool parseViewBenchArgs(int argc, char** argv, const char* name, ViewBenchArgs& a,
                               const std::function<bool(const char*, const char*)>& extra = {}) {
    if (argc < 2) return false;
    a.scenario = argv[1];
    for (int i = 2; i < argc; ++i) {
        const char* opt = argv[i];
        const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
        math::Viewpoint vp;
        bool ok = value != nullptr;
        if (ok && !std::strcmp(opt, "--view")) {
            ok = parseViewpoint(value, vp);
            if (ok) a.views.push_back(vp);
        } else if (ok && !std::strcmp(opt, "--size")) {
            const auto wh = parseSize(value);
            ok = wh.has_value();
            if (ok) std::tie(a.width, a.height) = *wh;
        } else if (ok && !std::strcmp(opt, "--frames")) {
            a.frames = std::max(1, std::atoi(value));
        } else if (ok && !std::strcmp(opt, "--passes")) {
            a.passes = std::max(1, std::atoi(value));
        } else {
            ok = ok && extra && extra(opt, value);
        }
        if (!ok) {
            std::fprintf(stderr, "%s: bad or unknown argument %s\n", name, opt);
            return false;
        }
        ++i;
    }
    return true;
}

/** @brief Resident set now (MB), from /proc/self/statm; 0 where unavailable. */
inline double currentRssMb() {
    FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0.0;
    unsigned long long size = 0, resident = 0;
    const int n = std::fscanf(f, "%llu %llu", &size, &resident);
    std::fclose(f);
    return n == 2 ? double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0) : 0.0;
}

}  // namespace kiosk::bench
