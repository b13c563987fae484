#!/usr/bin/env bash
# The Debian package end to end: cpack -G DEB, lintian (no errors), apt-get install ./geokiosk.deb,
# what it installed (user, conffile, unit not started, stripped binary), the installed binary
# playing the installed demo playlist headless, apt-get purge (user and conffile gone).
#   deb_install_test.sh BUILD_DIR REPO_ROOT
# Installs into the running system, so it runs only as root (CI containers) and only when no
# geokiosk package is installed already; it always purges what it installed. Exit 77 = skipped.
set -u
BUILD=$1
ROOT=$2
skip() {
    if [[ "${KIOSK_REQUIRE_DEB:-}" == 1 ]]; then echo "FAIL: $1"; exit 1; fi
    echo "SKIP: $1"; exit 77
}
[[ $(id -u) -eq 0 ]] || skip "not root: the package test installs into the system"
command -v apt-get >/dev/null && command -v cpack >/dev/null || skip "needs apt-get and cpack"
if dpkg-query -W -f='${Status}' geokiosk 2>/dev/null | grep -q "install ok installed"; then
    skip "a geokiosk package is already installed; not touching it"
fi
[[ -f "$ROOT/data/generated/rainier.gpkg" ]] || skip "demo store missing (run tools/prepare-demo.sh)"

pass=0 fail=0
check() {  # check DESCRIPTION CMD...
    local what=$1; shift
    if "$@" >/dev/null 2>&1; then echo "ok:   $what"; pass=$((pass + 1)); else echo "FAIL: $what"; fail=$((fail + 1)); fi
}
out=$(mktemp -d)
installed=0
cleanup() {
    if [[ $installed -eq 1 ]]; then DEBIAN_FRONTEND=noninteractive apt-get purge -y -qq geokiosk >/dev/null 2>&1; fi
    rm -rf "$out"
}
trap cleanup EXIT

(cd "$BUILD" && cpack -G DEB -B "$out" >"$out/cpack.log" 2>&1) || { tail -20 "$out/cpack.log"; echo "FAIL: cpack"; exit 1; }
deb=$(ls "$out"/geokiosk_*.deb 2>/dev/null | head -1)
[[ -n "$deb" ]] || { echo "FAIL: no .deb written"; exit 1; }
echo "built $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB)"
if command -v lintian >/dev/null; then
    lintian --fail-on error "$deb" >"$out/lintian.log" 2>&1
    rc=$?
    grep -E "^E: " "$out/lintian.log" | head -20
    check "lintian: no errors" test $rc -eq 0
else
    skip "lintian is not installed (apt-get install lintian)"
fi

DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$deb" >"$out/apt.log" 2>&1
rc=$?
[[ $rc -eq 0 ]] && installed=1
check "apt-get install ./$(basename "$deb")" test $rc -eq 0
[[ $rc -eq 0 ]] || { tail -20 "$out/apt.log"; exit 1; }
check "geokiosk user exists" getent passwd geokiosk
check "/etc/geokiosk/kiosk.json is a conffile" grep -qx /etc/geokiosk/kiosk.json /var/lib/dpkg/info/geokiosk.conffiles
check "unit installed" test -f /lib/systemd/system/geokiosk.service
check "unit not enabled" test ! -e /etc/systemd/system/multi-user.target.wants/geokiosk.service
check "binary stripped (no .symtab)" bash -c "! readelf -S /usr/bin/geokiosk | grep -q '\.symtab'"
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/share/glvnd/egl_vendor.d/50_mesa.json GALLIUM_DRIVER=llvmpipe
(cd / && env -u DISPLAY -u WAYLAND_DISPLAY /usr/bin/geokiosk play /etc/geokiosk/kiosk.json --display headless \
    --size 64x36 --frames 30 --listen 127.0.0.1:0 >"$out/play.log" 2>&1)
rc=$?
check "installed binary plays the installed demo playlist headless (exit $rc)" test $rc -eq 0
check "it played the demo entry" grep -q "entry 1/1: /usr/share/geokiosk/scenarios/demo/rainier.json" "$out/play.log"
[[ $rc -eq 0 ]] || tail -10 "$out/play.log"

DEBIAN_FRONTEND=noninteractive apt-get purge -y -qq geokiosk >"$out/purge.log" 2>&1
rc=$?
[[ $rc -eq 0 ]] && installed=0
check "apt-get purge" test $rc -eq 0
check "user removed on purge" bash -c "! getent passwd geokiosk"
check "conffile removed on purge" test ! -e /etc/geokiosk/kiosk.json
echo "$pass passed, $fail failed"
[[ $fail -eq 0 ]]
