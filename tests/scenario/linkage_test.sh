#!/usr/bin/env bash
# The kiosk runtime links only what it draws with (issue 14): its dynamic section names no GDAL,
# netCDF or OpenImageIO (nor does anything it loads), and `geokiosk import` still works by
# exec'ing geokiosk-import from the same folder.
#   linkage_test.sh BUILD/geokiosk REPO_ROOT
set -u
GK=$1
ROOT=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { echo "ok:   $*"; pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }
FORBIDDEN='libgdal|libnetcdf|libOpenImageIO'

needed=$(readelf -d "$GK" | grep NEEDED)
[[ -n "$needed" ]] && ok "readelf -d lists the runtime's libraries" || bad "readelf -d $GK printed no NEEDED"
if grep -Eq "$FORBIDDEN" <<<"$needed"; then bad "runtime NEEDED: $(grep -E "$FORBIDDEN" <<<"$needed")"
else ok "runtime NEEDED has no GDAL/netCDF/OpenImageIO"; fi
# Transitively too (a static library could drag one in through another shared library).
if ldd "$GK" | grep -Eq "$FORBIDDEN"; then bad "runtime loads: $(ldd "$GK" | grep -E "$FORBIDDEN")"
else ok "nothing the runtime loads is GDAL/netCDF/OpenImageIO"; fi
# FFmpeg (video export) is a module loaded only when a video is written: over a hundred libraries
# (x264, x265, libvpx, librsvg, ...) a playing kiosk never maps.
if ldd "$GK" | grep -Eq 'libavcodec|libavformat|libswscale'; then bad "runtime loads FFmpeg: $(ldd "$GK" | grep -E 'libav|libsw')"
else ok "nothing the runtime loads at start is FFmpeg"; fi
if readelf -d "$(dirname "$GK")/geokiosk-av.so" | grep -q libavcodec; then ok "geokiosk-av.so links libavcodec"
else bad "geokiosk-av.so does not link libavcodec"; fi
# The importer is the one that has them.
if readelf -d "$(dirname "$GK")/geokiosk-import" | grep -q libgdal; then ok "geokiosk-import links GDAL"
else bad "geokiosk-import does not link GDAL"; fi

# Importing through the one CLI: the exec keeps arguments, output and exit status.
DEM=$ROOT/data/rainier/mt_rainier_90m.tif
"$GK" import elevation "$DEM" --store "$tmp/s.gpkg" --name elevation --quiet 2>"$tmp/err"
rc=$?
[[ $rc -eq 0 ]] && ok "geokiosk import elevation exits 0" || { bad "import exit $rc"; cat "$tmp/err"; }
if "$GK" info "$tmp/s.gpkg" 2>&1 | grep -q "elevation \[elevation\]"; then ok "info lists the imported layer"
else bad "info does not list the imported elevation"; "$GK" info "$tmp/s.gpkg"; fi
"$GK" import topographic --store "$tmp/s.gpkg" --name shade --quiet 2>"$tmp/err"
rc=$?
[[ $rc -eq 0 ]] && ok "geokiosk import topographic exits 0" || { bad "topographic exit $rc"; cat "$tmp/err"; }
"$GK" import elevaton "$DEM" --store "$tmp/s.gpkg" 2>"$tmp/err"
rc=$?
[[ $rc -eq 2 ]] && ok "a usage error of the importer still exits 2" || bad "usage error exit $rc"
# Without the importer beside it: one line and exit 3 (cannot run here).
cp "$GK" "$tmp/geokiosk"
"$tmp/geokiosk" import elevation "$DEM" --store "$tmp/t.gpkg" 2>"$tmp/err"
rc=$?
if [[ $rc -eq 3 ]] && grep -q "cannot run the importer .*geokiosk-import" "$tmp/err"; then
    ok "missing importer: exit 3 naming it"
else bad "missing importer: exit $rc: $(cat "$tmp/err")"; fi

echo "$pass passed, $fail failed"
[[ $fail -eq 0 ]]
