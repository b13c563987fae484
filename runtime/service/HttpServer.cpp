#include "runtime/service/HttpServer.h"

#include <charconv>
#include <httplib.h>
#include <thread>

namespace kiosk::service {

std::optional<ListenAddress> parseListenAddress(std::string_view text, std::string& why) {
    const auto colon = text.rfind(':');
    if (colon == std::string_view::npos || colon == 0) {
        why = "--listen wants HOST:PORT (e.g. 127.0.0.1:9100), got '" + std::string(text) + "'";
        return std::nullopt;
    }
    ListenAddress a;
    a.host.assign(text.substr(0, colon));
    const std::string_view p = text.substr(colon + 1);
    auto [end, ec] = std::from_chars(p.data(), p.data() + p.size(), a.port);
    if (p.empty() || ec != std::errc() || end != p.data() + p.size() || a.port < 0 ||
        a.port > 65535) {
        why = "--listen port must be 0-65535, got '" + std::string(p) + "'";
        return std::nullopt;
    }
    return a;
}

struct HttpServer::Impl {
    httplib::Server server;
    HttpEndpoints endpoints;
    std::thread thread;
};

HttpServer::HttpServer() : mImpl(std::make_unique<Impl>()) {}
HttpServer::~HttpServer() {
    stop();
}

bool HttpServer::start(const ListenAddress& address, HttpEndpoints endpoints, std::string& why) {
    Impl& impl = *mImpl;
    impl.endpoints = std::move(endpoints);
    httplib::Server& s = impl.server;
    // Two workers: a scrape and a control request at once; more clients wait in the backlog.
    s.new_task_queue = [] { return new httplib::ThreadPool(2); };
    s.set_read_timeout(5, 0);
    s.set_write_timeout(5, 0);
    s.set_payload_max_length(4096);  // control requests carry no body
    const HttpEndpoints* ep = &impl.endpoints;

    s.Get("/health", [ep](const httplib::Request&, httplib::Response& res) {
        const HealthVerdict v = evaluateHealth(ep->snapshots->read(), ep->now(), ep->stallSeconds);
        res.status = v.status;
        res.set_content(v.body, "application/json");
    });
    s.Get("/metrics", [ep](const httplib::Request&, httplib::Response& res) {
        const ServiceSnapshot snap = ep->snapshots->read();
        ProcessFigures proc;
        proc.rssBytes = readRssBytes();
        proc.heapBytes = readHeapInUseBytes();
        proc.uptimeSeconds = ep->now() - snap.startedAt;
        res.set_content(renderMetrics(snap, proc), kMetricsContentType);
    });
    s.Post(R"(/control/([a-z]+))", [ep](const httplib::Request& req, httplib::Response& res) {
        const int auth = ep->token.check(req.get_header_value("Authorization"));
        if (auth != 200) {
            res.status = auth;
            if (auth == 401) res.set_header("WWW-Authenticate", "Bearer");
            res.set_content(auth == 403 ? "control is disabled: no token file configured\n"
                                        : "missing or wrong bearer token\n",
                            "text/plain");
            return;
        }
        std::string bad;
        bool notFound = false;
        auto cmd = parseControl(req.matches[1].str(), req.get_param_value("t"),
                                req.get_param_value("r"), bad, notFound);
        const auto param = [&req](const char* name) -> std::optional<std::string> {
            if (!req.has_param(name)) return std::nullopt;
            return req.get_param_value(name);
        };
        if (cmd && cmd->action == ControlAction::Lens && !parseLensMove(cmd->lens, param, bad))
            cmd.reset();
        if (!cmd) {
            res.status = notFound ? 404 : 400;
            res.set_content(bad + "\n", "text/plain");
            return;
        }
        if (!ep->control->push(*cmd)) {
            res.status = 503;
            res.set_content("too many control requests waiting\n", "text/plain");
            return;
        }
        res.status = 200;
        res.set_content(std::string(controlActionName(cmd->action)) + " queued\n", "text/plain");
    });

    if (address.port == 0) {
        mPort = s.bind_to_any_port(address.host);
        if (mPort <= 0) {
            why = "cannot listen on " + address.host + ":0";
            return false;
        }
    } else {
        if (!s.bind_to_port(address.host, address.port)) {
            why = "cannot listen on " + address.host + ":" + std::to_string(address.port) +
                  " (address in use or not local?)";
            return false;
        }
        mPort = address.port;
    }
    impl.thread = std::thread([&s] { s.listen_after_bind(); });
    return true;
}

void HttpServer::stop() {
    if (!mImpl || !mImpl->thread.joinable()) return;
    mImpl->server.stop();
    mImpl->thread.join();
}

}  // namespace kiosk::service
