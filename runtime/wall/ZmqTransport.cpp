#include "runtime/wall/ZmqTransport.h"

#include <cerrno>
#include <zmq.hpp>

namespace kiosk::wall {
namespace {

std::optional<Bytes> receiveOne(zmq::socket_t& s, std::chrono::microseconds timeout) {
    zmq::pollitem_t item{s.handle(), 0, ZMQ_POLLIN, 0};
    // zmq::poll takes milliseconds; sub-millisecond waits spin on a zero timeout instead.
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(timeout);
    zmq::message_t msg;
    try {
        if (zmq::poll(&item, 1, ms) <= 0) return std::nullopt;
        if (!s.recv(msg, zmq::recv_flags::dontwait)) return std::nullopt;
    } catch (const zmq::error_t& e) {
        // A signal (SIGTERM, SIGINT) interrupted the wait: nothing received; the frame loop
        // sees the stop request and exits cleanly.
        if (e.num() == EINTR) return std::nullopt;
        throw;
    }
    const auto* p = static_cast<const std::uint8_t*>(msg.data());
    return Bytes(p, p + msg.size());
}

Diagnostics endpointError(const std::string& endpoint, const char* what, const zmq::error_t& e) {
    Diagnostics d;
    d.error("WALL_ENDPOINT", endpoint, "",
            std::string("cannot ") + what + " " + endpoint + ": " + e.what());
    return d;
}

}  // namespace

struct LeaderTransport::Impl {
    zmq::context_t ctx{1};
    zmq::socket_t pub{ctx, zmq::socket_type::pub};
    zmq::socket_t pull{ctx, zmq::socket_type::pull};
};

LeaderTransport::LeaderTransport() : mImpl(std::make_unique<Impl>()) {}
LeaderTransport::~LeaderTransport() = default;

Result<std::unique_ptr<LeaderTransport>> LeaderTransport::bind(const SyncSettings& sync) {
    std::unique_ptr<LeaderTransport> t(new LeaderTransport());
    for (auto* s : {&t->mImpl->pub, &t->mImpl->pull}) s->set(zmq::sockopt::linger, 0);
    try {
        t->mImpl->pub.bind(sync.stateEndpoint);
    } catch (const zmq::error_t& e) {
        return endpointError(sync.stateEndpoint, "bind", e);
    }
    try {
        t->mImpl->pull.bind(sync.readyEndpoint);
    } catch (const zmq::error_t& e) {
        return endpointError(sync.readyEndpoint, "bind", e);
    }
    return t;
}

void LeaderTransport::publish(std::span<const std::uint8_t> m) {
    // PUB never blocks: a subscriber that cannot keep up loses messages, not the wall.
    (void)mImpl->pub.send(zmq::const_buffer(m.data(), m.size()), zmq::send_flags::dontwait);
}

std::pair<std::string, std::string> LeaderTransport::endpoints() const {
    return {mImpl->pub.get(zmq::sockopt::last_endpoint),
            mImpl->pull.get(zmq::sockopt::last_endpoint)};
}

std::optional<Bytes> LeaderTransport::receive(std::chrono::microseconds timeout) {
    return receiveOne(mImpl->pull, timeout);
}

struct FollowerTransport::Impl {
    zmq::context_t ctx{1};
    zmq::socket_t sub{ctx, zmq::socket_type::sub};
    zmq::socket_t push{ctx, zmq::socket_type::push};
};

FollowerTransport::FollowerTransport() : mImpl(std::make_unique<Impl>()) {}
FollowerTransport::~FollowerTransport() = default;

Result<std::unique_ptr<FollowerTransport>> FollowerTransport::connect(const SyncSettings& sync) {
    std::unique_ptr<FollowerTransport> t(new FollowerTransport());
    for (auto* s : {&t->mImpl->sub, &t->mImpl->push}) s->set(zmq::sockopt::linger, 0);
    // Reports to a leader that is not (yet, or any more) there are dropped, not queued: a stale
    // ready must not reach a restarted leader.
    t->mImpl->push.set(zmq::sockopt::immediate, 1);
    t->mImpl->sub.set(zmq::sockopt::subscribe, "");
    try {
        t->mImpl->sub.connect(sync.stateEndpoint);
    } catch (const zmq::error_t& e) {
        return endpointError(sync.stateEndpoint, "connect to", e);
    }
    try {
        t->mImpl->push.connect(sync.readyEndpoint);
    } catch (const zmq::error_t& e) {
        return endpointError(sync.readyEndpoint, "connect to", e);
    }
    return t;
}

void FollowerTransport::send(std::span<const std::uint8_t> m) {
    (void)mImpl->push.send(zmq::const_buffer(m.data(), m.size()), zmq::send_flags::dontwait);
}

std::optional<Bytes> FollowerTransport::receive(std::chrono::microseconds timeout) {
    return receiveOne(mImpl->sub, timeout);
}

}  // namespace kiosk::wall
