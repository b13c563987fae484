#!/usr/bin/env bash
# Longer fuzzing campaigns than CI's smoke runs (ctest -L fuzz runs each target for 8-25 s).
#   tools/fuzz.sh BUILD_DIR [SECONDS] [TARGET...]
# TARGET: scenario store tile colour times sww (default: all), SECONDS per target (default 600).
# Each target keeps its corpus in BUILD_DIR/tests/fuzz/corpus-TARGET and starts from the seeds in
# tests/fuzz/seeds/ (scenario: scenarios/broken and tests/unit/config/data). A crash writes
# crash-* in the working directory; rerun one input with `BUILD_DIR/tests/fuzz/kiosk_T_fuzzer FILE`.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:?usage: tools/fuzz.sh BUILD_DIR [SECONDS] [TARGET...]}
SECONDS_PER=${2:-600}
shift $(( $# >= 2 ? 2 : 1 ))
TARGETS=("$@")
[[ ${#TARGETS[@]} -gt 0 ]] || TARGETS=(scenario store tile colour times sww)
cd "$ROOT"
for t in "${TARGETS[@]}"; do
    bin=$BUILD/tests/fuzz/kiosk_${t}_fuzzer
    [[ -x $bin ]] || { echo "fuzz: $bin missing (needs clang++ and libclang-rt-*-dev)" >&2; exit 2; }
    asan=detect_leaks=1 flags=()
    case $t in
        scenario) seeds=(scenarios/broken tests/unit/config/data) ;;
        tile) seeds=(tests/fuzz/seeds/tiles) ;;
        *) seeds=(tests/fuzz/seeds/$t) ;;
    esac
    # As SwwFuzzSmoke (tests/fuzz/CMakeLists.txt): libnetcdf allocates what a header claims, so
    # allocations above 1 GB fail (null) instead of counting as findings.
    if [[ $t == sww ]]; then
        asan+=:allocator_may_return_null=1:max_allocation_size_mb=1024
        flags=(-malloc_limit_mb=100000)
    fi
    mkdir -p "$BUILD/tests/fuzz/corpus-$t"
    echo "fuzz: $t for ${SECONDS_PER}s"
    ASAN_OPTIONS=$asan "$bin" -max_total_time="$SECONDS_PER" -timeout=10 -rss_limit_mb=1536 \
        "${flags[@]}" -print_final_stats=1 "$BUILD/tests/fuzz/corpus-$t" "${seeds[@]}"
done
