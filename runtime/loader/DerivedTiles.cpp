#include "runtime/loader/DerivedTiles.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace kiosk::loader {

void DerivedTiles::keep(Track& t, int frame, const std::vector<float>& state) {
    // The latest state replaces the previous latest unless that one is a checkpoint.
    if (!t.states.empty()) {
        auto last = std::prev(t.states.end());
        if (last->first < frame && (last->first + 1) % kCheckpointEvery != 0) {
            t.bytes -= last->second.size() * sizeof(float);
            mBytes -= last->second.size() * sizeof(float);
            t.states.erase(last);
        }
    }
    auto [it, fresh] = t.states.try_emplace(frame, state);
    if (!fresh) return;
    t.bytes += state.size() * sizeof(float);
    mBytes += state.size() * sizeof(float);
}

std::size_t DerivedTiles::budget() const noexcept {
    return std::max(mBudget.value.load(std::memory_order_relaxed),
                    mTracksInView.value.load(std::memory_order_relaxed) * mLargestRunning);
}

void DerivedTiles::evict(const Key& keepKey) {
    const std::size_t limit = budget();
    if (mBytes <= limit) return;
    // Checkpoints first, least recently used tiles first (the one just computed last): the
    // latest states are what playing forward folds the next frame into; a checkpoint only
    // shortens a seek backwards.
    std::vector<std::pair<std::uint64_t, Track*>> byUse;
    for (auto& [key, track] : mTracks)
        if (track.states.size() > 1) byUse.emplace_back(track.lastUse, &track);
    std::sort(byUse.begin(), byUse.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& [use, t] : byUse) {
        if (mBytes <= limit) return;
        const auto latest = std::prev(t->states.end());
        for (auto it = t->states.begin(); it != latest;) {
            const std::size_t b = it->second.size() * sizeof(float);
            t->bytes -= b;
            mBytes -= b;
            it = t->states.erase(it);
        }
    }
    while (mBytes > limit && mTracks.size() > 1) {
        auto oldest = mTracks.end();
        for (auto it = mTracks.begin(); it != mTracks.end(); ++it)
            if (!(it->first == keepKey) &&
                (oldest == mTracks.end() || it->second.lastUse < oldest->second.lastUse))
                oldest = it;
        if (oldest == mTracks.end()) return;
        mBytes -= oldest->second.bytes;
        mTracks.erase(oldest);
    }
}

Diagnostics DerivedTiles::compute(int binding, const Derivation& d, io::StoreReader& reader,
                                  const std::string& sequence, int frame, const TileId& id,
                                  io::RasterTile& out) {
    Diagnostics diags;
    const io::SequenceInfo* seq = reader.info().findSequence(sequence);
    if (!seq || frame < 0 || std::size_t(frame) >= seq->frameTimes.size()) {
        diags.error("LOADER_DERIVED_FRAME", reader.info().path, sequence,
                    "no frame " + std::to_string(frame) + " to derive from");
        return diags;
    }
    const Key key{binding, id.packed()};
    Track& track = mTracks[key];
    track.lastUse = ++mUse;
    // Resume from the latest kept state at or before `frame`.
    std::vector<float> state;
    int done = -1;
    if (auto it = track.states.upper_bound(frame); it != track.states.begin()) {
        --it;
        state = it->second;
        done = it->first;
    }
    const std::size_t floats = std::size_t(d.stateFloats());
    // A frame read as the previous request's second frame is not read again. A frame whose tile
    // the store does not hold (STORE_TILE_MISSING: nothing valid there yet, e.g. where a flood
    // has not arrived) is all nodata: empty here, NaN of the tile's size once that is known.
    auto read = [&](int j) -> Result<std::vector<float>> {
        if (j == track.nextFrame) return track.next;
        Result<io::RasterTile> r = reader.readSequenceFrame(sequence, j, id);
        if (!r.ok()) {
            if (r.diagnostics.has("STORE_TILE_MISSING")) return std::vector<float>{};
            return r.diagnostics;
        }
        track.postsX = r->postsX;
        track.postsY = r->postsY;
        return std::move(r->values);
    };
    std::vector<int> absent;  // frames before the first the store holds for this tile
    auto begin = [&](std::size_t posts) {
        state.assign(posts * floats, 0.0f);
        d.start(state);
        const std::vector<float> none(posts, std::nanf(""));
        for (int a : absent)
            d.advance(state, none, seq->frameTimes[std::size_t(a)],
                      a > 0 ? seq->frameTimes[std::size_t(a) - 1] : std::nan(""));
        absent.clear();
    };
    for (int j = done + 1; j <= frame; ++j) {
        Result<std::vector<float>> values = read(j);
        if (!values.ok()) return values.diagnostics;
        if (values->empty()) {
            if (state.empty()) {
                absent.push_back(j);
                continue;
            }
            values->assign(state.size() / floats, std::nanf(""));
        }
        if (state.empty()) begin(values->size());
        if (state.size() != values->size() * floats) {
            diags.error("LOADER_DERIVED_FRAME", reader.info().path, sequence,
                        "frame " + std::to_string(j) + " of tile " + std::to_string(id.level) +
                            "/" + std::to_string(id.column) + "/" + std::to_string(id.row) +
                            " differs in size from the frames before it");
            return diags;
        }
        d.advance(state, *values, seq->frameTimes[std::size_t(j)],
                  j > 0 ? seq->frameTimes[std::size_t(j) - 1] : std::nan(""));
        ++mFolded;
        if ((j + 1) % kCheckpointEvery == 0 && j < frame) keep(track, j, state);
    }
    std::vector<float> next;
    bool nextAbsent = false;
    if (std::size_t(frame) + 1 < seq->frameTimes.size()) {
        Result<std::vector<float>> values = read(frame + 1);
        if (!values.ok()) return values.diagnostics;
        next = std::move(*values.value);
        nextAbsent = next.empty();
    }
    if (state.empty()) {
        // No frame up to k + 1 has data here: nothing to draw (the loader's Absent tile).
        if (next.empty()) {
            track.nextFrame = -1;
            diags.error("STORE_TILE_MISSING", reader.info().path, sequence,
                        "no frame up to " + std::to_string(frame + 1) + " holds tile " +
                            std::to_string(id.level) + "/" + std::to_string(id.column) + "/" +
                            std::to_string(id.row));
            return diags;
        }
        begin(next.size());  // frames 0..k all nodata, k + 1 arrives on screen
    }
    if (nextAbsent) next.assign(state.size() / floats, std::nanf(""));
    if (next.size() * floats != state.size()) next.clear();
    out.id = id;
    out.postsX = track.postsX;
    out.postsY = track.postsY;
    out.channels = loader::Derivation::kProductChannels;
    out.values.assign(state.size() / floats * std::size_t(out.channels), 0.0f);
    d.finish(state, next, out.values);
    track.nextFrame = next.empty() ? -1 : frame + 1;
    const std::size_t was = track.next.size() * sizeof(float), now = next.size() * sizeof(float);
    track.bytes = track.bytes - was + now;
    mBytes = mBytes - was + now;
    track.next = std::move(next);
    keep(track, frame, state);
    mLargestRunning = std::max(mLargestRunning, (state.size() + track.next.size()) * sizeof(float));
    evict(key);
    mBytesHeld.value.store(mBytes, std::memory_order_relaxed);
    return diags;
}

}  // namespace kiosk::loader
