#pragma once

#include "runtime/terrain/DetailSketch.h"
#include "runtime/terrain/GeometryImageWarp.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace kiosk::terrain {

/**
 * @brief The warped geometry image as a triangle mesh for the detail grid (no GL): what
 * runtime/shaders/warpgrid.vert reads. Vertex = 10 floats:
 *   x, y (metres from `origin`), z (data surface, absolute), data normal (3),
 *   amplitude (m), split octave o = log2(d0 / d_ij) - 0.5 (DS04 Eq. 1, half an octave
 *   conservative against swimming), border fade (0 on the region's border .. 1 inside),
 *   skirt depth (m; 0 for surface vertices).
 * Triangles: grid row t's cells are indices [rowStart[t], rowStart[t + 1]) (each cell split along
 * the diagonal that keeps both triangles counter-clockwise), then the skirts hanging from the
 * border, [rowStart[n - 1], indices.size()).
 */
struct WarpedGridMesh {
    static constexpr int kFloatsPerVertex = 10;
    glm::dvec2 origin{0.0};
    std::vector<float> vertices;
    std::vector<std::uint32_t> indices;
    std::vector<std::uint32_t> rowStart;  ///< n entries: n - 1 rows of cells, then the skirts
    std::vector<glm::dvec2> rowY;         ///< per row of cells: min and max world y
    std::uint32_t cellTriangles = 0;      ///< triangles of the surface (skirts excluded)
};

/**
 * @brief Build the mesh of `grid` over `sketch` (whose posts must all be finite); heights and
 * normals from `surface` where it answers (the drawn TIN itself), else from the sketch. The fade
 * reaches 1 at `fadeWidth` metres from the border; skirts hang `skirtDepth` metres.
 * Reuses `out`'s buffers.
 */
using SurfaceSampler = std::function<bool(const glm::dvec2& p, double& height, glm::dvec3& normal)>;
void buildWarpedGridMesh(const WarpGrid& grid, const DetailSketch& sketch, double fadeWidth,
                         double skirtDepth, WarpedGridMesh& out,
                         const SurfaceSampler& surface = {});

/** @brief Rows of cells [first, last) whose y range meets [minY, maxY]. */
void warpedGridRows(const WarpedGridMesh& mesh, double minY, double maxY, int& first, int& last);

}  // namespace kiosk::terrain
