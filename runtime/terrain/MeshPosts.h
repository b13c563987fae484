#pragma once

#include "runtime/math/Glm.h"
#include "runtime/terrain/RtinMesher.h"

#include <cstdint>
#include <vector>

namespace kiosk::terrain {

/**
 * @brief The heights a tile's TIN surface takes at the tile's posts: what the quadtree draws,
 * read back as a regular grid (the warped detail grid samples it so the hand-over to the
 * quadtree matches). Every surface triangle is scan-converted over the posts it covers;
 * posts under no triangle (holes) are NaN. Pure; any thread.
 */
struct MeshPosts {
    glm::dvec2 firstPost{0.0};  ///< world xy of post (0, 0): the tile's north-west post
    glm::dvec2 spacing{1.0};    ///< metres (x east, y south)
    int size = 0;               ///< posts per side
    std::vector<float> z;       ///< row-major, row 0 north
    std::vector<glm::vec3> n;   ///< the mesh's vertex normals interpolated the same way

    /** @brief Bilinear height at world `p`; NaN outside the posts or next to a hole. */
    double at(const glm::dvec2& p) const;
    /** @brief Post (i, j) nearest to world `p` (clamped); false outside the posts. */
    bool nearest(const glm::dvec2& p, int& i, int& j) const;
    /**
     * @brief The TIN itself at world `p`: height and normal interpolated in the triangle that
     * contains it (exactly what the rasteriser draws there); false outside the surface.
     */
    bool sample(const glm::dvec2& p, double& height, glm::dvec3& normal) const;

    /** @brief Per post cell, the surface triangles overlapping it (first index of each). */
    std::vector<std::uint32_t> cellStart, cellTriangles;
    std::vector<glm::vec3> vertices;  ///< the TIN's vertices in post coordinates (x, y) and z
    std::vector<glm::vec3> normals;
    std::vector<std::uint32_t> indices;  ///< surface triangles
};

MeshPosts meshPosts(const TileMesh& mesh);

}  // namespace kiosk::terrain
