#pragma once

#include "runtime/math/Camera.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

// The messages of the wall's sync protocol (docs/wall.md "Sync protocol"). ZeroMQ frames them;
// the payload is a fixed little-endian layout written field by field (never a struct memcpy), so
// nodes built by different compilers agree. Pure; any thread.
namespace kiosk::wall {

enum class MessageType : std::uint8_t { State = 1, Release = 2, Ready = 3, Stop = 4 };

/** @brief What every node draws for frame `frame` (published by the leader). */
struct FrameState {
    std::uint64_t frame = 0;
    double dataTime = 0;  ///< the scenario clock's time for this frame (epoch seconds)
    double stepTime = 0;  ///< wall-wide atomic steps: sequences show the pair bracketing this
    math::Viewpoint camera;
    std::uint64_t scenarioHash = 0;  ///< FNV-1a of the scenario's files (mismatch is reported)
    std::string scenarioId;          ///< the scenario file's name (for messages)
    // Clock state: followers plan their prefetch from it (scene::Playback).
    double rate = 0;
    double rangeStart = 0;
    double rangeEnd = 0;
    std::uint64_t seekSerial = 0;
    std::uint8_t rangeMode = 0;
    bool paused = false;
    /** Briefing chapter shown (-1: none): its layer overrides and caption apply on every node. */
    std::int32_t chapter = -1;
};

/** @brief A node's report for one frame (followers PUSH, the leader PULLs). */
struct Ready {
    std::uint32_t screen = 0;  ///< screen index in the wall file (identifies the node's process)
    std::uint64_t frame = 0;
    bool resident = false;      ///< drawn with every tile it needs resident
    bool stepResident = false;  ///< the pair at the frame's dataTime is resident (may step to it)
    std::uint64_t scenarioHash = 0;
};

/** @brief The leader's swap release for `frame`. */
struct Release {
    std::uint64_t frame = 0;
    bool byDeadline = false;       ///< some node was not ready and was dropped
    std::uint32_t readyNodes = 0;  ///< nodes (leader included) that were ready in time
};

std::vector<std::uint8_t> encode(const FrameState& m);
std::vector<std::uint8_t> encode(const Ready& m);
std::vector<std::uint8_t> encode(const Release& m);
std::vector<std::uint8_t> encodeStop();

/** @brief The type of a message, or nullopt for an empty/unknown one. */
std::optional<MessageType> messageType(std::span<const std::uint8_t> bytes);
std::optional<FrameState> decodeState(std::span<const std::uint8_t> bytes);
std::optional<Ready> decodeReady(std::span<const std::uint8_t> bytes);
std::optional<Release> decodeRelease(std::span<const std::uint8_t> bytes);

}  // namespace kiosk::wall
