// Session: the memory budgets beside the tile cache (MemoryBudgets.h) - what is in effect, what
// is held, and the font atlas degraded to fit.
#include "runtime/app/MemoryBudgets.h"
#include "runtime/app/Session.h"
#include "runtime/color/TransferFunction.h"
#include "runtime/core/Log.h"
#include "runtime/io/StoreReader.h"
#include "runtime/platform/CompilerPages.h"

namespace kiosk::app {
namespace {
constexpr const char* kTag = "session";
}

std::vector<std::pair<std::string, double>> Session::budgets() const {
    auto out = mScene->budgets();
    const EffectiveBudgets b = effectiveBudgets(mScenario->memoryBudgets);
    const MemoryUsage u = memoryUsage();
    out.insert(out.end(), {{"lut_bytes", double(b.lutBytes)},
                           {"lut_bytes_used", double(u.lutBytes)},
                           {"mapping_bytes", double(b.mappingBytes)},
                           {"mapping_bytes_used", double(u.mappingBytes)},
                           {"font_atlas_bytes", double(b.fontAtlasBytes)},
                           {"font_atlas_bytes_used", double(u.fontAtlasBytes)},
                           {"sqlite_page_cache_bytes_per_connection",
                            double(io::StoreReader::pageCacheBytes())}});
    // llvmpipe's compiler code handed back between compiles (platform/CompilerPages.h).
    const platform::CompilerPagesStats cp = platform::compilerPagesStats();
    out.insert(out.end(), {{"compiler_code_bytes_mapped", double(cp.mappedBytes)},
                           {"compiler_code_releases", double(cp.releases)}});
    return out;
}

Session::MemoryUsage Session::memoryUsage() const {
    const scene::SceneMemoryUsage scene = mScene->memoryUsage();
    MemoryUsage u;
    u.lutBytes = scene.lutBytes + mLegendLuts.size() * std::uint64_t(color::kMinLutSize) * 4;
    u.mappingBytes = scene.mappingBytes;
    u.fontAtlasBytes = mOverlay ? mFontAtlasBytes : 0;
    return u;
}

int Session::budgetedFontPx(int wantedPx) {
    const config::MemoryBudget& set = mScenario->memoryBudgets.fontAtlas;
    const std::uint64_t budget = effectiveBudgets(mScenario->memoryBudgets).fontAtlasBytes;
    std::uint64_t need = 0;
    const int px = fontPxWithin(render::FontAtlas::defaultFontPath(), wantedPx, budget,
                                mFontAtlasBytes, &need);
    if (px != wantedPx && mFontWarnedPx != wantedPx) {
        // Degrade, do not refuse: smaller (or no) text is no reason to leave the display dark.
        mFontWarnedPx = wantedPx;
        const std::string where = set.set() ? set.file + ":" + std::to_string(set.line) + ":" +
                                                  std::to_string(set.column) + ": " + set.pointer
                                            : std::string("default font atlas budget");
        const std::string drawn =
            px > 0 ? "drawn at " + std::to_string(px) + " px"
                   : "no text drawn (not even " + std::to_string(kMinFontPx) + " px fits)";
        KIOSK_LOG_WARN(kTag,
                       "%s: overlay text at %d px needs a font atlas of %llu bytes, over the "
                       "budget of %s (%llu bytes): %s",
                       where.c_str(), wantedPx, static_cast<unsigned long long>(need),
                       bytesText(budget).c_str(), static_cast<unsigned long long>(budget),
                       drawn.c_str());
    }
    return px;
}

}  // namespace kiosk::app
