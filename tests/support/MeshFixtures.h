#pragma once

#include <functional>

#include "runtime/render/MeshData.h"

namespace kiosk::test {

/**
 * @brief Full-resolution regular grid mesh of `n x n` posts spaced `spacing` metres, heights
 * from `height(x, y)` (metres, x east, y north from the south-west corner), normals by central
 * differences. Used as the brute-force reference in render tests.
 */
render::MeshData gridMesh(int n, double spacing, const std::function<double(double, double)>& height);

}  // namespace kiosk::test
