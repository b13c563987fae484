#pragma once

#include "config/KioskFile.h"
#include "config/Scenario.h"
#include "runtime/anim/ScenarioClock.h"
#include "runtime/core/Result.h"
#include "runtime/gl/Context.h"
#include "runtime/service/Playlist.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace kiosk::app {

class Session;

/**
 * @brief A kiosk file's playlist on the render thread: opens (and so validates) each entry when
 * it is about to go on screen, skips a broken one with one log line and a /health warning, and
 * says when the entry on screen is done. Broken entries are tried again on the next pass, so a
 * fixed file comes back without a restart.
 */
class KioskPlaylist {
public:
    explicit KioskPlaylist(config::KioskFile file);

    /**
     * @brief Open the next playable entry from the current one moving by `step` (0: the current
     * one itself, for the first open). nullptr when no entry can be opened now (every one broken
     * or outside its window); `errors` then holds the last failure.
     */
    std::unique_ptr<Session> open(int step, const gl::Caps& caps, Diagnostics& errors);
    /** @brief The entry on screen opened again (its store was replaced); keeps its timing. */
    Result<std::unique_ptr<Session>> reopen(const gl::Caps& caps) const;
    /** @brief The entry on screen from a scenario already read and checked (play's reload
     *  worker): only the GL half, with the kiosk file's budgets. */
    Result<std::unique_ptr<Session>> create(std::unique_ptr<config::Scenario> scenario,
                                            const gl::Caps& caps) const;
    /** @brief The entry on screen has had its time, loops or window. */
    bool finished(const anim::ScenarioClock& clock) const;
    /** @brief Black-curtain opacity of the fade transition now (0 with "cut"). */
    float curtain() const;

    const config::KioskFile& file() const noexcept { return mFile; }
    int index() const noexcept { return mIndex; }
    int size() const noexcept { return int(mFile.playlist.size()); }
    const std::filesystem::path& currentScenario() const { return mFile.playlist[mIndex].scenario; }
    std::uint64_t skipped() const noexcept { return mSkipped; }
    /** @brief One line per entry that was broken when last tried ("/playlist/1: ..."). */
    std::vector<std::string> warnings() const;

private:
    void applyBudgets(config::Scenario& s) const;

    config::KioskFile mFile;
    std::vector<service::PlaylistRule> mRules;
    std::vector<bool> mBroken;
    std::vector<std::string> mBrokenWhy;
    int mIndex = 0;
    double mEntryStart = 0;
    std::uint64_t mSkipped = 0;
};

}  // namespace kiosk::app
