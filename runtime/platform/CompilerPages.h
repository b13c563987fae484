#pragma once

#include <cstddef>
#include <cstdint>

namespace kiosk::platform {

/**
 * @brief Gives the kernel back the code pages of the GL driver's shader compiler between
 * compiles (issue 14, docs/performance.md §5).
 *
 * llvmpipe compiles every shader variant with LLVM. While it does, the kernel maps libLLVM's
 * code into the process by 64 KiB fault-around blocks: ~49 MB of clean file pages resident
 * (a third of the 1080p flight's peak RSS) that nothing uses again until the next compile.
 * releaseCompilerPages() hands those pages back with madvise(MADV_PAGEOUT): they are clean,
 * so nothing is written; a later compile faults back the pages it needs (from the page cache
 * while the kernel still has them, else from disk). Pages another process maps too are left
 * alone by the kernel. Any driver that compiles with libLLVM gets the same treatment (e.g.
 * radeonsi); one without it finds nothing to do.
 *
 * Render thread only. The first call reads /proc/self/maps once (after the GL context exists);
 * every later call is at most one madvise per mapping and never allocates.
 */
struct CompilerPagesStats {
    std::size_t mappedBytes = 0;  ///< executable bytes of the compiler's mappings found
    std::uint64_t releases = 0;   ///< calls that advised the kernel
};

/**
 * @brief madvise(MADV_PAGEOUT) the compiler's code if at least `intervalSeconds` passed since
 * the last release (monotonic clock; the first call always releases). True if it did.
 */
bool releaseCompilerPages(double intervalSeconds);

CompilerPagesStats compilerPagesStats();

}  // namespace kiosk::platform
