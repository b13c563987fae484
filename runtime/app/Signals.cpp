#include "runtime/app/Signals.h"

#include <csignal>

namespace kiosk::app {
namespace {
volatile std::sig_atomic_t gStop = 0;
extern "C" void onStopSignal(int) { gStop = 1; }
}  // namespace

void installStopSignals() {
    struct sigaction sa {};
    sa.sa_handler = onStopSignal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

bool stopRequested() noexcept { return gStop != 0; }
void resetStopRequest() noexcept { gStop = 0; }

}  // namespace kiosk::app
