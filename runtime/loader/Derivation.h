#pragma once

#include <cstddef>
#include <span>
#include <string>

namespace kiosk::loader {

/**
 * @brief Values a layer kind derives from the stored frames of a sequence on the loader thread
 * (derived products, layers/products/). The loader knows no product: it reads the frames, keeps
 * the running state per tile and hands the result to the cache like a stored frame.
 *
 * Two shapes, chosen by stateFloats():
 * - **cumulative** (> 0): the tile of key frame k holds, per post, the state after frames 0..k
 *   (maximum so far, arrival time, duration above a threshold) together with frames k and k + 1,
 *   as four floats (kProductChannels, uploaded as one RGBA16F texture), so the shader combines
 *   the state with the value on screen between the two frames from ONE texture read. The loader
 *   advances a running state one stored frame at a time and keeps it (and checkpoints) per tile
 *   under a byte budget, so playing forward reads one frame per step; a seek backwards restarts
 *   from the nearest checkpoint at or before k. The result depends on k only, never on the order
 *   of requests.
 * - **per frame** (0): the tile of frame k combines frame k of the sequence with frame k of a
 *   companion sequence of the same store (hazard class from depth and velocity), one float per
 *   post like a stored frame.
 * Implementations are immutable and shared with the render thread: every method is const.
 */
class Derivation {
public:
    /** @brief Floats per post of a cumulative product's tile (RGBA). */
    static constexpr int kProductChannels = 4;

    virtual ~Derivation() = default;
    /** @brief Floats of running state per post; 0 for a per-frame derivation. */
    virtual int stateFloats() const { return 0; }
    /** @brief Cumulative: reset `state` (stateFloats() per post) to "before the first frame". */
    virtual void start(std::span<float> state) const { (void)state; }
    /**
     * @brief Cumulative: fold in frame `values` (NaN = nodata) stored at `time`, the frame before
     * it at `previousTime` (NaN for the first frame); times in seconds since the epoch, as the
     * store keeps them.
     */
    virtual void advance(std::span<float> state, std::span<const float> values, double time,
                         double previousTime) const {
        (void)state, (void)values, (void)time, (void)previousTime;
    }
    /**
     * @brief Cumulative: the tile's kProductChannels floats per post from the state after frame
     * k and the values of frame k + 1 (`next`; empty when k is the last frame).
     */
    virtual void finish(std::span<const float> state, std::span<const float> next,
                        std::span<float> out) const {
        (void)state, (void)next, (void)out;
    }
    /** @brief Per frame: the sequence read at the same frame and tile, empty for none. */
    virtual const std::string& companion() const {
        static const std::string none;
        return none;
    }
    /** @brief Per frame: replace `values` by the derived ones, `other` = companion frame. */
    virtual void combine(std::span<float> values, std::span<const float> other) const {
        (void)values, (void)other;
    }
};

}  // namespace kiosk::loader
