#include "runtime/terrain/MeshCells.h"

namespace kiosk::terrain {

std::uint32_t cellMortonCode(std::uint32_t x, std::uint32_t y) {
    std::uint32_t code = 0;
    for (int b = 0; b < TileMesh::kMaxCellLevels; ++b)
        code |= ((x >> b) & 1u) << (2 * b) | ((y >> b) & 1u) << (2 * b + 1);
    return code;
}

void meshCellBounds(const TileMesh& mesh, int x, int y, glm::dvec2& min, glm::dvec2& max) {
    const double px = mesh.postSpacing.x, py = mesh.postSpacing.y;
    const double cp = double(mesh.cellPosts);
    const int last = mesh.cellsPerSide() - 1;
    // Post (i, j) sits at origin + ((i + 0.5) px, -(j + 0.5) py); rows run south.
    min.x = mesh.origin.x + (x * cp + 0.5) * px - (x == 0 ? 0.5 * px : 0.0);
    max.x = mesh.origin.x + ((x + 1) * cp + 0.5) * px + (x == last ? 0.5 * px : 0.0);
    max.y = mesh.origin.y - (y * cp + 0.5) * py + (y == 0 ? 0.5 * py : 0.0);
    min.y = mesh.origin.y - ((y + 1) * cp + 0.5) * py - (y == last ? 0.5 * py : 0.0);
}

bool meshRangesInRect(const TileMesh& mesh, const glm::dvec2& rectMin, const glm::dvec2& rectMax,
                      std::vector<IndexRange>& out) {
    out.clear();
    if (mesh.cellPosts <= 0 || mesh.cellLevels < 0 || mesh.cellLevels > TileMesh::kMaxCellLevels)
        return false;
    // A hair of slack (1e-6 of a cell) so a rectangle touching a cell edge keeps that cell.
    const glm::dvec2 slack = mesh.postSpacing * double(mesh.cellPosts) * 1e-6;
    auto append = [&out](std::uint32_t first, std::uint32_t end) {
        if (end <= first) return;
        if (!out.empty() && out.back().first + out.back().count == first)
            out.back().count += end - first;
        else
            out.push_back(IndexRange{first, end - first});
    };
    // Intersecting cells in Morton order, once per section: runs come out in index order.
    for (int section = 0; section < 2; ++section) {
        const auto& starts = section == 0 ? mesh.surfaceCellStart : mesh.skirtCellStart;
        const int cells = mesh.cellCount();
        for (int code = 0; code < cells; ++code) {
            int x = 0, y = 0;
            for (int b = 0; b < mesh.cellLevels; ++b) {
                x |= ((code >> (2 * b)) & 1) << b;
                y |= ((code >> (2 * b + 1)) & 1) << b;
            }
            glm::dvec2 cmin, cmax;
            meshCellBounds(mesh, x, y, cmin, cmax);
            if (cmax.x + slack.x < rectMin.x || cmin.x - slack.x > rectMax.x ||
                cmax.y + slack.y < rectMin.y || cmin.y - slack.y > rectMax.y)
                continue;
            append(starts[std::size_t(code)], starts[std::size_t(code) + 1]);
        }
    }
    return true;
}

}  // namespace kiosk::terrain
