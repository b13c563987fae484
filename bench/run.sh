#!/usr/bin/env bash
# Run every benchmark; each prints ONE JSON object (with its baseline measured in the same run).
#   bench/run.sh [BUILD]     (BUILD defaults to build/; the demo store must exist:
#                             tools/prepare-demo.sh BUILD/geokiosk)
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build}
cd "$ROOT"
"$ROOT/tools/prepare-demo.sh" "$BUILD/geokiosk" >&2
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/share/glvnd/egl_vendor.d/50_mesa.json
export GALLIUM_DRIVER=llvmpipe
"$BUILD/bench/bench-frame" scenarios/demo/rainier.json --frames ${KIOSK_BENCH_FRAMES:-60}
"$BUILD/bench/bench-import"                 # 4k DEM vs gdal_translate + gdaladdo (--sizes 4096,16384)
"$BUILD/bench/hillshade/hillshade_bench"    # 4k DEM vs gdaldem hillshade (--with-16k)
