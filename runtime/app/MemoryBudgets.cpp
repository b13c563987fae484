#include "runtime/app/MemoryBudgets.h"

#include "runtime/color/TransferFunction.h"
#include "runtime/io/StoreReader.h"
#include "runtime/render/FontAtlas.h"
#include "runtime/render/MappingSet.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <set>
#include <unistd.h>

namespace kiosk::app {
namespace {

// RGBA8 textures: a layer's ramp (legends) and the stack's copy with its below, above and nodata
// texels (render::makeEdgedLutTexture); a legend of a function no layer draws has the ramp only.
constexpr std::uint64_t kLegendLutBytes = std::uint64_t(color::kMinLutSize) * 4;
constexpr std::uint64_t kLayerLutBytes =
    kLegendLutBytes + std::uint64_t(color::kMinLutSize + 3) * 4;

std::uint64_t orDefault(const config::MemoryBudget& b, std::uint64_t fallback) {
    return b.set() ? std::uint64_t(b.bytes) : fallback;
}

void refuse(Diagnostics& d, const config::Scenario& sc, const config::MemoryBudget& b,
            const char* code, const char* scenarioPointer, const char* setting,
            const std::string& what, std::uint64_t need, std::uint64_t budget) {
    const std::string scenarioFile =
        sc.sourceFiles.empty() ? std::string() : sc.sourceFiles.front().string();
    std::string message = "scenario " + scenarioFile + " needs " + bytesText(need) + " (" +
                          std::to_string(need) + " bytes) of " + what + ", over ";
    if (b.set()) {
        Diagnostic& e = d.error(code, b.file, b.pointer,
                                message + "this kiosk's budget of " + bytesText(budget) + " (" +
                                    std::to_string(budget) + " bytes)");
        e.line = b.line;
        e.column = b.column;
        return;
    }
    Diagnostic& e = d.error(code, scenarioFile, scenarioPointer,
                            message + "the default budget of " + bytesText(budget));
    e.hint = std::string("a kiosk file may raise it (budgets.") + setting + ")";
}

}  // namespace

std::uint64_t BudgetDefaults::mappingBytes() {
    static const std::uint64_t bytes = [] {  // the machine does not change: asked once
        const std::uint64_t most =
            std::uint64_t(render::MappingSet::kMaxMappings) *
            render::MappingSet::bytesPerLayer(render::MappingSet::kSceneLayerSize);
        const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
        if (pages <= 0 || page <= 0) return most;
        return std::min(most, std::uint64_t(pages) * std::uint64_t(page) / 8);
    }();
    return bytes;
}

EffectiveBudgets effectiveBudgets(const config::MemoryBudgets& set) {
    EffectiveBudgets e;
    e.lutBytes = orDefault(set.luts, BudgetDefaults::kLutBytes);
    e.mappingBytes = orDefault(set.mappings, BudgetDefaults::mappingBytes());
    e.fontAtlasBytes = orDefault(set.fontAtlas, BudgetDefaults::kFontAtlasBytes);
    e.sqlitePageCacheBytes =
        orDefault(set.sqlitePageCache, std::uint64_t(io::StoreReader::kDefaultPageCacheBytes));
    return e;
}

MemoryNeeds memoryNeeds(const config::Scenario& sc) {
    // The same rules TerrainScene applies: a LUT per data or sequence layer, an array layer per
    // mapping image file, per scalar mapping (plus its LUT row) and two for routes; a legend of
    // a function no layer draws builds its own LUT (Session::drawLegend).
    MemoryNeeds n;
    std::set<std::string> layerTransfers;
    for (const auto& l : sc.layers) {
        if (l.kind != config::LayerKind::Data && l.kind != config::LayerKind::Sequence &&
            l.kind != config::LayerKind::Difference)
            continue;
        ++n.luts;
        n.lutBytes += kLayerLutBytes;
        layerTransfers.insert(l.transfer);
    }
    std::set<std::string> legendTransfers;  // Session keeps one LUT per function
    for (const auto& legend : sc.overlays.legends)
        if (legend.enabled && sc.findTransfer(legend.transfer) &&
            !layerTransfers.count(legend.transfer) &&
            legendTransfers.insert(legend.transfer).second) {
            ++n.luts;
            n.lutBytes += kLegendLutBytes;
        }
    std::set<std::filesystem::path> images;
    bool route = false;
    for (const auto& m : sc.projectiveMappings) {
        if (m.route) {
            route = true;
        } else if (!m.image.empty()) {
            images.insert(m.image);
        } else if (sc.findTransfer(m.transfer)) {
            ++n.mappingLayers;
            ++n.luts;
            n.lutBytes += render::MappingSet::bytesPerLut();
        }
    }
    n.mappingLayers += int(images.size()) + (route ? 2 : 0);
    n.mappingBytes = std::uint64_t(n.mappingLayers) *
                     render::MappingSet::bytesPerLayer(render::MappingSet::kSceneLayerSize);
    return n;
}

Diagnostics checkMemoryBudgets(const config::Scenario& sc) {
    Diagnostics d;
    const EffectiveBudgets b = effectiveBudgets(sc.memoryBudgets);
    const MemoryNeeds n = memoryNeeds(sc);
    if (n.lutBytes > b.lutBytes)
        refuse(d, sc, sc.memoryBudgets.luts, "BUDGET_LUTS", "/layers", "lutBytes",
               "transfer-function LUTs (" + std::to_string(n.luts) + " LUTs)", n.lutBytes,
               b.lutBytes);
    if (n.mappingBytes > b.mappingBytes)
        refuse(d, sc, sc.memoryBudgets.mappings, "BUDGET_MAPPINGS", "/projectiveMappings",
               "mappingBytes",
               "projective-mapping arrays (" + std::to_string(n.mappingLayers) + " layers of " +
                   std::to_string(render::MappingSet::kSceneLayerSize) + "x" +
                   std::to_string(render::MappingSet::kSceneLayerSize) + ")",
               n.mappingBytes, b.mappingBytes);
    return d;
}

int fontPxWithin(const std::string& fontPath, int wantedPx, std::uint64_t budgetBytes,
                 std::uint64_t& atlasBytes, std::uint64_t* wantedBytes) {
    atlasBytes = 0;
    auto bytesAt = [&](int px) -> std::optional<std::uint64_t> {
        auto atlas = render::FontAtlas::build(fontPath, px);
        if (!atlas) return std::nullopt;
        return std::uint64_t(atlas->width()) * std::uint64_t(atlas->height()) * 2;
    };
    // Usually the wanted size fits: one build. Otherwise the atlas grows with the text size:
    // binary search for the largest size that fits.
    const auto wanted = bytesAt(wantedPx);
    if (!wanted) return 0;
    if (wantedBytes) *wantedBytes = *wanted;
    if (*wanted <= budgetBytes) {
        atlasBytes = *wanted;
        return wantedPx;
    }
    int lo = kMinFontPx, hi = wantedPx - 1, best = 0;
    while (lo <= hi) {
        const int px = (lo + hi) / 2;
        const auto bytes = bytesAt(px);
        if (!bytes) return 0;
        if (*bytes <= budgetBytes) {
            best = px;
            atlasBytes = *bytes;
            lo = px + 1;
        } else {
            hi = px - 1;
        }
    }
    return best;
}

std::string bytesText(std::uint64_t bytes) {
    char text[32];
    if (bytes >= (std::uint64_t(1) << 20))
        std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
    else
        std::snprintf(text, sizeof text, "%.1f KiB", double(bytes) / 1024.0);
    return text;
}

}  // namespace kiosk::app
