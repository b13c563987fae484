#pragma once

#include "runtime/service/Control.h"
#include "runtime/service/ServiceState.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

// The kiosk's HTTP endpoints on cpp-httplib (Debian libcpp-httplib-dev): GET /health,
// GET /metrics, POST /control/<action>. A thin transport over ServiceState and Control; handlers
// only copy the snapshot or push to the queue, never touch the render thread's objects, and no
// endpoint opens a file named by the request.
namespace kiosk::service {

struct ListenAddress {
    std::string host = "127.0.0.1";
    int port = 0;  ///< 0: any free port (logged)
};
/** @brief "HOST:PORT" (IPv4 or a name; port 0-65535). Nullopt with `why` on a bad value. */
std::optional<ListenAddress> parseListenAddress(std::string_view text, std::string& why);

struct HttpEndpoints {
    const SnapshotBox* snapshots = nullptr;
    ControlQueue* control = nullptr;
    TokenGuard token;
    double stallSeconds = 5.0;    ///< /health says 503 after this long without a frame
    std::function<double()> now;  ///< monotonic seconds (same clock as the snapshot's)
};

class HttpServer {
public:
    HttpServer();
    ~HttpServer();
    HttpServer(const HttpServer&) = delete;
    HttpServer& operator=(const HttpServer&) = delete;

    /** @brief Bind and start serving on a thread of its own; false with `why` if binding failed. */
    bool start(const ListenAddress& address, HttpEndpoints endpoints, std::string& why);
    /** @brief The port actually bound (useful with port 0). */
    int port() const noexcept { return mPort; }
    void stop();

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
    int mPort = 0;
};

}  // namespace kiosk::service
