#!/usr/bin/env bash
# Build the demo's store from the bundled DEM with `geokiosk import` (README quick start).
#   tools/prepare-demo.sh [BUILD/geokiosk]
# Output: data/generated/rainier.gpkg (elevation pyramid, hillshade, SYNTHETIC flood sequence and a
# second SYNTHETIC run of it for the comparison lens).
# Skipped when the store is newer than its inputs and the geokiosk binary.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
GEOKIOSK=${1:-$ROOT/build/geokiosk}
BIN=$(dirname "$GEOKIOSK")
DEM=$ROOT/data/rainier/mt_rainier_90m.tif
OUT=$ROOT/data/generated
STORE=$OUT/rainier.gpkg
mkdir -p "$OUT"
if [[ -f "$STORE" && "$STORE" -nt "$DEM" && "$STORE" -nt "$GEOKIOSK" && "$STORE" -nt "$0" ]]; then
    echo "prepare-demo: $STORE is up to date"
    exit 0
fi
rm -f "$STORE"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "prepare-demo: importing $DEM"
"$GEOKIOSK" import elevation "$DEM" --store "$work/rainier.gpkg" --name elevation --fill-voids --quiet
"$GEOKIOSK" import topographic --store "$work/rainier.gpkg" --elevation elevation --name hillshade \
    --quiet
"$GEOKIOSK" import topographic --store "$work/rainier.gpkg" --elevation elevation --name normals \
    --normals --quiet
echo "prepare-demo: making the SYNTHETIC flood (bathtub fill, not a model run)"
"$BIN/make-synthetic-flood" "$DEM" "$work/flood" --steps 13 --rise 150 \
    --start 2026-03-14T00:00:00Z >/dev/null
"$GEOKIOSK" import sequence "$work"/flood/flood_*.tif --store "$work/rainier.gpkg" \
    --name flood_depth --times "$work/flood/times.csv" --units m --variable depth --quiet
# A second SYNTHETIC run (water rising 100 m instead of 150 m, same times) for the comparison
# lens scenarios (scenarios/demo/rainier-compare*.json).
"$BIN/make-synthetic-flood" "$DEM" "$work/flood_b" --steps 13 --rise 100 \
    --start 2026-03-14T00:00:00Z >/dev/null
"$GEOKIOSK" import sequence "$work"/flood_b/flood_*.tif --store "$work/rainier.gpkg" \
    --name flood_depth_rise100 --times "$work/flood_b/times.csv" --units m \
    --variable depth --quiet
mv "$work/rainier.gpkg" "$STORE"
echo "prepare-demo: wrote $STORE"
"$GEOKIOSK" info "$STORE"
