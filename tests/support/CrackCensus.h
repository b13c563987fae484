#pragma once

#include "runtime/gl/RenderTarget.h"

namespace kiosk::test {

/** @brief What crackPixels() found in one frame. */
struct CrackCount {
    int cracks = 0;   ///< clear-colour pixels enclosed by terrain
    int sky = 0;      ///< clear-colour pixels in all (0: the method saw no background at all)
    int firstX = -1;  ///< first crack pixel (row-major), for the failure message
    int firstY = -1;
};

/**
 * @brief The crack census of issue 12 (../shared/tools/crack-census.sh, ported): pixels within
 * ±2 of the clear colour (Session: 158,181,204) are flood-filled, 8-connected, from the image
 * border and from the overlay panels (bounding boxes, grown by 3 px, of blobs of >= 100 px of
 * panel-over-clear colour 53,63,76 ±3, plus the progress-bar band 4..12 px above the bottom
 * edge); every clear-colour pixel the fill does not reach is a crack. `img` rows run top-down
 * (RenderTarget::readColor).
 */
CrackCount crackPixels(const gl::Image& img);

}  // namespace kiosk::test
