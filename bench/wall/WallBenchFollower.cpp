// bench-wall-follower: one follower process of bench-wall (sync only, no GL): runs FollowerSync,
// reports ready as soon as a state arrives, and at Stop writes "frame swap_us" lines (monotonic
// clock, comparable across processes) to OUT.
//   bench-wall-follower STATE_ENDPOINT READY_ENDPOINT SCREEN OUT
#include "runtime/wall/FollowerSync.h"
#include "runtime/wall/ZmqTransport.h"

#include "bench/common/SteadyTime.h"

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

using namespace kiosk;
using Us = std::chrono::microseconds;

namespace {

using bench::nowUs;

/** Swap times (µs, monotonic, shared by all processes) to `outPath` at Stop. */
int runFollower(const std::string& state, const std::string& ready, std::uint32_t screen,
                const std::string& outPath) {
    auto t = wall::FollowerTransport::connect({state, ready, 100.0});
    if (!t) return 3;
    wall::FollowerSync f(screen, 30.0);
    std::vector<std::pair<std::uint64_t, double>> swaps;
    const double until = nowUs() + 120e6;
    while (!f.stopped() && nowUs() < until) {
        if (auto m = (*t)->receive(Us(20000))) {
            switch (wall::messageType(*m).value_or(wall::MessageType::Ready)) {
                case wall::MessageType::State:
                    f.onState(*wall::decodeState(*m), nowUs() / 1e6);
                    break;
                case wall::MessageType::Release:
                    f.onRelease(*wall::decodeRelease(*m));
                    break;
                case wall::MessageType::Stop:
                    f.onStop();
                    break;
                default:
                    break;
            }
        }
        if (f.takeStateToDraw())
            if (auto r = f.drawn(true, true, 0)) (*t)->send(wall::encode(*r));
        if (f.swapDue()) {
            const double us = nowUs();
            swaps.emplace_back(f.swapped(), us);
        }
    }
    std::ofstream out(outPath);
    for (const auto& [frame, us] : swaps) out << frame << ' ' << std::int64_t(us) << '\n';
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 5) return 2;
    return runFollower(argv[1], argv[2], std::uint32_t(std::atoi(argv[3])), argv[4]);
}
