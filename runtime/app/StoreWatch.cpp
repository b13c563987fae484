#include "runtime/app/StoreWatch.h"

#include "runtime/core/Log.h"
#include "runtime/io/StoreReader.h"

#include <sys/stat.h>

namespace kiosk::app {
namespace {
constexpr const char* kTag = "store-watch";
constexpr double kPollSeconds = 1.0;

/** @brief Open the store and read its metadata as the session would (any thread). */
std::string checkStore(const std::filesystem::path& path) {
    auto reader = io::StoreReader::open(path);
    if (!reader) {
        const Diagnostic* d = reader.diagnostics.firstError();
        return d ? d->format() : "cannot be opened";
    }
    return {};
}
}  // namespace

StoreWatch::~StoreWatch() {
    if (mCheck.valid()) mCheck.wait();
}

std::optional<StoreWatch::Stamp> StoreWatch::stampOf(const std::filesystem::path& p) {
    struct stat st {};
    if (::stat(p.c_str(), &st) != 0) return std::nullopt;
    Stamp s;
    s.dev = st.st_dev;
    s.ino = st.st_ino;
    s.size = std::uint64_t(st.st_size);
    s.mtimeNs = std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
    return s;
}

void StoreWatch::watch(const config::Scenario& scenario) {
    if (mCheck.valid()) mCheck.wait();
    mCheck = {};
    mStores.clear();
    mSwapReady = false;
    mDegradedWhy.clear();
    for (const auto& [id, ref] : scenario.stores) {
        Store s;
        s.path = ref.path;
        if (auto st = stampOf(ref.path)) s.shown = *st;
        mStores.push_back(std::move(s));
    }
}

void StoreWatch::finishCheck() {
    if (!mCheck.valid() || mCheck.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return;
    const std::string why = mCheck.get();
    Store& s = mStores[mCheckIndex];
    if (why.empty()) {
        KIOSK_LOG_INFO(kTag, "%s was replaced and passed its check; switching at the next step",
                       s.path.c_str());
        mSwapReady = true;
    } else {
        KIOSK_LOG_ERROR(kTag, "%s was replaced by a broken store, keeping the old picture: %s",
                        s.path.c_str(), why.c_str());
        s.rejected = mCheckStamp;
    }
}

void StoreWatch::poll(double now) {
    finishCheck();
    if (mSwapReady || mCheck.valid() || now - mLastPoll < kPollSeconds) return;
    mLastPoll = now;
    std::string degraded;
    for (std::size_t i = 0; i < mStores.size(); ++i) {
        Store& s = mStores[i];
        const auto st = stampOf(s.path);
        if (!st) {
            if (!s.missing)
                KIOSK_LOG_WARN(kTag, "%s is gone; keeping the picture from the open file",
                               s.path.c_str());
            s.missing = true;
            degraded = s.path.string() + ": store file is gone (picture kept from the open file)";
            continue;
        }
        if (s.missing) KIOSK_LOG_INFO(kTag, "%s is back", s.path.c_str());
        s.missing = false;
        if (*st == s.shown || (s.rejected && *st == *s.rejected)) continue;
        // A new file (rename) or one rewritten in place: check it away from the render thread.
        mCheckIndex = i;
        mCheckStamp = *st;
        mCheck = std::async(std::launch::async, checkStore, s.path);
        break;
    }
    mDegradedWhy = degraded;
}

std::vector<std::pair<std::string, std::uint64_t>> StoreWatch::files() const {
    std::vector<std::pair<std::string, std::uint64_t>> out;
    for (const auto& s : mStores) out.emplace_back(s.path.string(), s.shown.ino);
    return out;
}

}  // namespace kiosk::app
