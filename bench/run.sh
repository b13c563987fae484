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
"$BUILD/bench/bench-frame" scenarios/demo/rainier.json --frames ${KIOSK_BENCH_FRAMES:-60} \
    --target-fps ${KIOSK_BENCH_TARGET_FPS:-10}
# The seed paper's data set (Wahl 2004): Puget Sound 1025^2 at 160 m, terrain only.
PUGET=$ROOT/../shared/data/puget_sound_heightmap/ps_height_1k.png
if [[ -f "$PUGET" ]]; then
    data=$BUILD/bench-data
    mkdir -p "$data"
    [[ -f "$data/puget.gpkg" ]] || "$BUILD/geokiosk" import elevation "$PUGET" --store "$data/puget.gpkg" \
        --pixel-size 160 --z-scale 0.1 --quiet 2>/dev/null
    cat >"$data/puget.json" <<'JSON'
{ "version": 1, "title": "Puget Sound (benchmark)", "stores": { "p": "puget.gpkg" },
  "terrain": { "store": "p", "tauGeom": 1, "tauTex": 1 }, "layers": [] }
JSON
    "$BUILD/bench/bench-frame" "$data/puget.json" --frames ${KIOSK_BENCH_FRAMES:-60}
else
    echo '{"benchmark":"frame","scenario":"puget","skipped":"../shared/data not present"}'
fi
"$BUILD/bench/bench-meshes" data/generated/rainier.gpkg $([[ -f $BUILD/bench-data/puget.gpkg ]] && echo $BUILD/bench-data/puget.gpkg)  # stored compressed meshes vs meshing on load
"$BUILD/bench/bench-detail"                 # procedural detail: off / warped grid / regular grid
"$BUILD/bench/bench-mappings"               # Table 1 of Trapp & Doellner: 0/1/4/16/27/64 mappings
"$BUILD/bench/bench-compare"                # comparison lens vs the same scenario without it
"$BUILD/bench/bench-import"                 # 4k DEM vs gdal_translate + gdaladdo (--sizes 4096,16384)
"$BUILD/bench/hillshade/hillshade_bench"    # 4k DEM vs gdaldem hillshade (--with-16k)
"$BUILD/bench/bench-replay" scenarios/demo/rainier.json --anuga "$ROOT/../shared/data/anuga_sww_flood_timeseries/cairns.sww"  # sequences at 1280x720/1920x1080 vs the fill bound
"$BUILD/bench/bench-products" "$ROOT/../shared/data/anuga_sww_flood_timeseries/cairns.sww"  # 0/1/3 derived product layers on the ANUGA replay
# Kiosk operation (issue 15): soak (KIOSK_SOAK_FRAMES, default 1,000,000), restart, /metrics scrape.
/usr/bin/python3 "$ROOT/bench/kiosk/kiosk_bench.py" soak "$BUILD/geokiosk" "$ROOT" --frames ${KIOSK_SOAK_FRAMES:-1000000}
/usr/bin/python3 "$ROOT/bench/kiosk/kiosk_bench.py" restart "$BUILD/geokiosk" "$ROOT"
/usr/bin/python3 "$ROOT/bench/kiosk/kiosk_bench.py" scrape "$BUILD/geokiosk" "$ROOT"
"$BUILD/bench/bench-wall" scenarios/demo/rainier.json   # swap barrier, 4/16 follower processes vs one node's frame
"$BUILD/bench/bench-export" scenarios/demo/rainier.json --frames ${KIOSK_BENCH_FRAMES:-60}  # 1080p export vs PNG vs rendering alone
"$BUILD/bench/bench-yuv420"   # the export's RGBA -> YUV 4:2:0 against libswscale (its previous path)
# Out-of-core at W04 scale (issue 20): SYNTHETIC 16k^2 vs 4k^2 DEM, import, first complete frame, flight.
/usr/bin/python3 "$ROOT/bench/outofcore/outofcore_bench.py" "$BUILD"
# Occlusion culling on vs off (issue 20), same session, alternating passes: three oblique views
# at Mount Rainier (demo; its 20 km tiles leave little to cull) and three low views into a
# SYNTHETIC 4096^2 DEM at 10 m (2.5 km tiles; make-synthetic-dem, imported once into bench-data).
"$BUILD/bench/bench-occlusion" scenarios/demo/rainier.json --view 594500,5189560,1800,120,-2,15000 \
    --view 594500,5189560,3500,180,-3,9000 --view 594500,5189560,2500,300,-4,20000
data=$BUILD/bench-data
mkdir -p "$data"
if [[ ! -f "$data/synthetic4k.gpkg" ]]; then
    "$BUILD/make-synthetic-dem" 4096 "$data/synthetic4k.tif" >&2
    "$BUILD/geokiosk" import elevation "$data/synthetic4k.tif" --store "$data/synthetic4k.gpkg" --quiet
fi
cat >"$data/synthetic4k.json" <<'JSON'
{ "version": 1, "title": "SYNTHETIC 4096^2 DEM (occlusion benchmark)",
  "stores": { "dem": "synthetic4k.gpkg" }, "terrain": { "store": "dem", "tauGeom": 2, "tauTex": 1 },
  "transferFunctions": { "relief": { "label": "Elevation", "units": "m", "stops": [
      { "value": -500, "color": "#3f7f4f" }, { "value": 1500, "color": "#c9b98a" },
      { "value": 3000, "color": "#9c8a78" }, { "value": 4600, "color": "#ffffff" } ] } },
  "layers": [ { "id": "relief", "kind": "data", "source": { "store": "dem", "layer": "elevation" },
                "transfer": "relief" } ] }
JSON
"$BUILD/bench/bench-occlusion" "$data/synthetic4k.json"
# Impostors (issue 20): far terrain drawn vs not drawn (far plane cut) vs a one-fetch quad over
# its pixels, alternating passes: the upper bound of any impostor win on llvmpipe.
"$BUILD/bench/bench-impostor" scenarios/demo/rainier.json --view 594500,5189560,1800,120,-8,40000
"$BUILD/bench/bench-impostor" "$data/synthetic4k.json" --view 520480,5279520,2289,0,-6,12000
# How many frames a far-terrain impostor stays within 1 px along the demo's camera tour.
"$BUILD/bench/bench-impostor-validity" scenarios/demo/rainier.json --fps 30
"$BUILD/bench/bench-impostor-validity" scenarios/demo/rainier.json --fps 60 --level 3
# GPU texture compression (issue 20): ASTC 4x4 (astcenc) PSNR per imagery layer, encode cost,
# and what llvmpipe holds per compressed texture vs RGBA8 (built when libastcenc-dev is there).
if [[ -x "$BUILD/bench/bench-texcompress" ]]; then
    # The running scene with the stored ASTC blocks vs the PNG tiles: a copy of the demo store
    # with `geokiosk import textures` (made once, ~30 s).
    astc=$BUILD/bench-data/rainier-astc.gpkg
    if [[ ! -f "$astc" || "$astc" -ot data/generated/rainier.gpkg ]]; then
        mkdir -p "$BUILD/bench-data" && cp data/generated/rainier.gpkg "${astc%.gpkg}-part.gpkg"
        "$BUILD/geokiosk" import textures --store "${astc%.gpkg}-part.gpkg" --quiet &&
            mv "${astc%.gpkg}-part.gpkg" "$astc"
    fi
    GEOKIOSK_ALLOW_PATHS=$BUILD/bench-data "$BUILD/bench/bench-texcompress" \
        data/generated/rainier.gpkg --scenario scenarios/demo/rainier.json --compressed "$astc"
else
    echo '{"benchmark":"texture_compression","skipped":"libastcenc-dev not installed"}'
fi
# Local TINs (issue 20, Baumann 2000): import time, store size, TIN vs grid triangles, frame time with/without.
/usr/bin/python3 "$ROOT/bench/tins/tins_bench.py" "$BUILD"
