#!/usr/bin/env bash
# End-to-end checks of the geokiosk command line (docs/cli.md): exit statuses, one-line
# messages naming the culprit, and that `render` of the demo writes a recognisable picture.
#   cli_test.sh GEOKIOSK REPO_ROOT
# Prints "N passed, M failed" and exits non-zero on any failure.
set -u
GK=$1
ROOT=$2
cd "$ROOT"
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/share/glvnd/egl_vendor.d/50_mesa.json GALLIUM_DRIVER=llvmpipe
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0

# expect STATUS PATTERN CMD...: run CMD, check its exit status and that stderr matches PATTERN.
expect() {
    local want=$1 pattern=$2
    shift 2
    "$@" >"$tmp/out" 2>"$tmp/err"
    local got=$?
    if [[ $got -ne $want ]]; then
        echo "FAIL: $* -> exit $got, want $want"; sed 's/^/    /' "$tmp/err" | head -5; fail=$((fail + 1)); return
    fi
    if [[ -n "$pattern" ]] && ! grep -Eq -- "$pattern" "$tmp/err"; then
        echo "FAIL: $* -> stderr does not match /$pattern/"; sed 's/^/    /' "$tmp/err" | head -5
        fail=$((fail + 1)); return
    fi
    echo "ok:   $*"; pass=$((pass + 1))
}

DEMO=scenarios/demo/rainier.json
# Usage errors: exit 2, with a hint.
expect 2 "unknown command 'rendr' \(did you mean 'render'\?\)" "$GK" rendr
expect 2 "usage" "$GK"
expect 2 "unknown option --sise \(did you mean --size\?\)" "$GK" render $DEMO --out "$tmp/x.png" --sise 10x10
expect 2 "--size wants WIDTHxHEIGHT" "$GK" render $DEMO --out "$tmp/x.png" --size 12
expect 2 "--out is required" "$GK" render $DEMO
expect 2 "--time and --from/--to are exclusive" "$GK" render $DEMO --out "$tmp/d/" --time +1h --from +0 --to +1h
expect 2 "wants an ISO 8601" "$GK" render $DEMO --out "$tmp/x.png" --time yesterday
expect 2 "--out must end in .png .*\.mp4, \.mkv or \.webm" "$GK" render $DEMO --out "$tmp/x.avi"
expect 2 "--crf applies to .mp4 and .webm" "$GK" render $DEMO --out "$tmp/x.mkv" --crf 20
expect 2 "--crf wants an integer 0..51" "$GK" render $DEMO --out "$tmp/x.mp4" --crf 99
expect 2 "--preset applies to .mp4" "$GK" render $DEMO --out "$tmp/x.webm" --preset fast
expect 2 "--preset wants one of ultrafast" "$GK" render $DEMO --out "$tmp/x.mp4" --preset quick
expect 2 "needs an even --size, got 321x181" "$GK" render $DEMO --out "$tmp/x.mp4" --size 321x181
expect 2 "--display wants auto\|kms\|x11\|wayland\|headless.*did you mean 'kms'" "$GK" play $DEMO --display kmz
expect 2 "--reference wants lod or full" "$GK" render $DEMO --out "$tmp/x.png" --reference exact
expect 2 "--occlusion-culling wants on or off" "$GK" render $DEMO --out "$tmp/x.png" --occlusion-culling no
expect 2 "--target-fps wants a number" "$GK" play $DEMO --display headless --target-fps -5
# Bad input: exit 1, one line naming the file.
expect 1 "nope.json: scenario file not found" "$GK" render nope.json --out "$tmp/x.png"
expect 1 "scenarios/broken/unknown-transfer.json:[0-9]+:[0-9]+: /layers/1/transfer: unknown transfer function \"depht\" \(did you mean \"depth\"\?\)" \
    "$GK" validate scenarios/broken/unknown-transfer.json
expect 1 "scenarios/broken/bad-json.json:[0-9]+:[0-9]+:" "$GK" render scenarios/broken/bad-json.json --out "$tmp/x.png"
expect 1 "missing.gpkg: store file does not exist" "$GK" info "$tmp/missing.gpkg"
expect 1 "" "$GK" import elevation "$tmp/missing.tif" --store "$tmp/s.gpkg"
# Cannot run here: exit 3 (this machine has no /dev/dri; with DISPLAY unset there is no display).
if [[ ! -e /dev/dri ]]; then
    expect 3 "no DRM device" "$GK" play $DEMO --display kms
    expect 3 "no display.*--display headless" env -u DISPLAY -u WAYLAND_DISPLAY "$GK" play $DEMO
fi
# Topographic import: a normal map into a copy of the demo store (issue 7).
expect 2 "--shadows applies to the hillshade, not to --normals" "$GK" import topographic --store "$tmp/n.gpkg" --normals --shadows
if [[ -f data/generated/rainier.gpkg ]]; then
    cp data/generated/rainier.gpkg "$tmp/n.gpkg"
    expect 0 "" "$GK" import topographic --store "$tmp/n.gpkg" --normals --name relief_normals --quiet
    if "$GK" info "$tmp/n.gpkg" 2>&1 | grep -q "^budgets: cache sized to the view's working set"; then
        echo "ok:   info prints the default budgets"; pass=$((pass + 1))
    else echo "FAIL: info prints no budgets"; fail=$((fail + 1)); fi
    if "$GK" info "$tmp/n.gpkg" 2>&1 | grep -q "relief_normals \[imagery\]"; then
        echo "ok:   info lists the normal map"; pass=$((pass + 1))
    else echo "FAIL: info does not list relief_normals"; fail=$((fail + 1)); fi
    # GPU texture blocks (issue 20): a data layer is refused, the store untouched; usage exit 2.
    expect 1 "never lossy-compressed" "$GK" import textures --store "$tmp/n.gpkg" --layers elevation
    expect 2 "--quality wants fast" "$GK" import textures --store "$tmp/n.gpkg" --quality best
fi
# Everything shipped validates.
expect 0 "" "$GK" validate $DEMO
# Headless play runs frames and stops cleanly.
expect 0 "stopped cleanly" "$GK" play $DEMO --display headless --size 320x180 --frames 3
# play --stats: the same per-frame arrays as render, one entry per frame, and the budgets;
# --max-fps 0 is unthrottled (issue 14). Tiles arrive asynchronously, so the first frames may draw
# nothing on a loaded machine: 300 unthrottled frames give the loader time to deliver the root.
expect 0 "stopped cleanly" "$GK" play $DEMO --display headless --size 160x90 --frames 300 --max-fps 0 --stats "$tmp/play.json"
if /usr/bin/python3 - "$tmp/play.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
f = j["frames"]
keys = ["frame_ms", "tiles_drawn", "triangles", "resident_bytes", "data_time", "prefetch_depth"]
assert all(len(f[k]) == 300 for k in keys), {k: len(f.get(k, [])) for k in keys}
assert all(ms > 0 for ms in f["frame_ms"]) and max(f["tiles_drawn"]) > 0
assert j["summary"]["frames"] == 300 and j["summary"]["frames_dropped"] == 0
b = j["budgets"]
assert b["cache_gpu_sized_to_view"] == 1 and b["cache_gpu_bytes"] >= 32 << 20
assert b["upload_bytes_per_frame"] > 0 and b["view_working_set_gpu_bytes"] > 0
# Memory budgets (docs/kiosk.md): defaults, and the demo's two LUTs held.
assert b["lut_bytes"] == 1 << 20 and b["lut_bytes_used"] == 2 * 8204, b
assert b["mapping_bytes"] > 0 and b["font_atlas_bytes"] == 1 << 20
assert b["sqlite_page_cache_bytes_per_connection"] == 256 << 10
PY
then echo "ok:   play --stats writes per-frame arrays, summary and budgets"; pass=$((pass + 1))
else echo "FAIL: play --stats JSON"; fail=$((fail + 1)); fi
expect 2 "--max-fps wants a number >= 0" "$GK" play $DEMO --display headless --max-fps -1
# render writes a recognisable terrain: mostly not sky, deterministic across runs.
expect 0 "wrote 1 frame" "$GK" render $DEMO --out "$tmp/a.png" --time +3h --size 320x180 --stats "$tmp/s.json"
expect 0 "wrote 1 frame" "$GK" render $DEMO --out "$tmp/b.png" --time +3h --size 320x180
if cmp -s "$tmp/a.png" "$tmp/b.png"; then echo "ok:   render is deterministic"; pass=$((pass + 1));
else echo "FAIL: two renders of the same time differ"; fail=$((fail + 1)); fi
if grep -q '"tiles_drawn"' "$tmp/s.json" && grep -q '"p99"' "$tmp/s.json"; then
    echo "ok:   --stats has per-frame arrays and a summary"; pass=$((pass + 1))
else echo "FAIL: --stats JSON incomplete"; fail=$((fail + 1)); fi
if grep -q '"prefetch_depth"' "$tmp/s.json" && grep -q '"sequence_missing_frames"' "$tmp/s.json"; then
    echo "ok:   --stats has the sequence prefetch figures"; pass=$((pass + 1))
else echo "FAIL: --stats lacks prefetch_depth / sequence_missing_frames"; fail=$((fail + 1)); fi
# The demo clock runs 1200 data seconds per second: one hour is 3 s of playback, 3 frames at 1 fps
# plus the closing frame.
expect 0 "wrote 4 frames" "$GK" render $DEMO --out "$tmp/seq/" --from +0 --to +1h --fps 1 --size 160x90
[[ -f "$tmp/seq/000004.png" ]] && { echo "ok:   frame files numbered"; pass=$((pass + 1)); } || { echo "FAIL: no $tmp/seq/000004.png"; fail=$((fail + 1)); }

echo "$pass passed, $fail failed"
[[ $fail -eq 0 ]]
