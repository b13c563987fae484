#pragma once

#include "runtime/core/Result.h"
#include "runtime/wall/Wall.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

// The thin ZeroMQ transport of the wall sync (cppzmq): the leader binds a PUB socket (frame
// states and swap releases, in order) and a PULL socket (ready reports); followers connect a SUB
// and a PUSH. No protocol logic here: SwapBarrier and FollowerSync decide, this only moves
// bytes. Sockets have linger 0 so a node never hangs on exit because a peer is gone.
namespace kiosk::wall {

using Bytes = std::vector<std::uint8_t>;

class LeaderTransport {
public:
    /** @brief Bind both endpoints; one clear error if an endpoint is taken or malformed. */
    static Result<std::unique_ptr<LeaderTransport>> bind(const SyncSettings& sync);
    ~LeaderTransport();
    void publish(std::span<const std::uint8_t> message);
    /** @brief The endpoints as bound (a tcp "*" port resolved), state first. */
    std::pair<std::string, std::string> endpoints() const;
    /** @brief Next ready report, waiting at most `timeout` (0: only what is queued). */
    std::optional<Bytes> receive(std::chrono::microseconds timeout);

private:
    LeaderTransport();
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

class FollowerTransport {
public:
    static Result<std::unique_ptr<FollowerTransport>> connect(const SyncSettings& sync);
    ~FollowerTransport();
    /** @brief Queue a report for the leader; never blocks (dropped if the queue is full). */
    void send(std::span<const std::uint8_t> message);
    /** @brief Next message from the leader, waiting at most `timeout`. */
    std::optional<Bytes> receive(std::chrono::microseconds timeout);

private:
    FollowerTransport();
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

}  // namespace kiosk::wall
