#!/usr/bin/env bash
# geokiosk quick start (README): one script, two commands.
#   tools/quickstart.sh demo   install what is missing, build, prepare the demo data, play the demo
#   tools/quickstart.sh test   install what is missing (incl. test tools), build, run every test
# On a machine without a display, `demo` says so and renders the demo headless to PNG frames.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${KIOSK_BUILD_DIR:-$ROOT/build}
MODE=${1:-}
JOBS=${KIOSK_JOBS:-$(nproc)}

# Debian 12 packages. Runtime/build first, then what only the tests need.
BUILD_PKGS=(build-essential cmake ninja-build ccache pkg-config git
    libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libgbm-dev libdrm-dev libx11-dev
    libglm-dev libopenimageio-dev libsqlite3-dev nlohmann-json3-dev libgtest-dev
    libgdal-dev gdal-bin libnetcdf-dev libfreetype-dev fonts-dejavu-core
    libsystemd-dev libcpp-httplib-dev libwayland-dev wayland-protocols libzmq3-dev cppzmq-dev
    libavcodec-dev libavformat-dev libswscale-dev libavutil-dev
    libspng-dev libturbojpeg0-dev libmeshoptimizer-dev libastcenc-dev
    libcgal-dev libgmp-dev libmpfr-dev)
TEST_PKGS=(xvfb xauth glslang-tools clang-14 libclang-rt-14-dev python3-prometheus-client weston lintian ffmpeg
    python3-jsonschema)

usage() {
    echo "usage: tools/quickstart.sh demo|test" >&2
    exit 2
}
[[ "$MODE" == demo || "$MODE" == test ]] || usage

install_missing() {
    local wanted=("$@") missing=()
    for p in "${wanted[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    ((${#missing[@]} == 0)) && return 0
    if [[ $(id -u) -eq 0 ]]; then
        echo "quickstart: installing ${missing[*]}"
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq
        apt-get install -y -qq --no-install-recommends "${missing[@]}"
    else
        echo "quickstart: missing Debian packages; run this, then re-run the quick start:" >&2
        echo "  sudo apt-get install -y --no-install-recommends ${missing[*]}" >&2
        exit 1
    fi
}

build() {
    local werror=OFF
    [[ "${CI:-}" == true ]] && werror=ON
    cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DKIOSK_WERROR=$werror >/dev/null
    cmake --build "$BUILD" -j "$JOBS"
}

prepare_demo() {
    "$ROOT/tools/prepare-demo.sh" "$BUILD/geokiosk"
}

case "$MODE" in
demo)
    install_missing "${BUILD_PKGS[@]}"
    build
    prepare_demo
    scenario="$ROOT/scenarios/demo/rainier.json"
    set +e
    "$BUILD/geokiosk" play "$scenario"
    status=$?
    set -e
    if [[ $status -eq 3 ]]; then
        out="$ROOT/out/demo"
        echo "quickstart: no display here; rendering the demo headless to PNG frames instead"
        mkdir -p "$out"
        "$BUILD/geokiosk" render "$scenario" --out "$out/" --from +0 --to +9h --fps 2 \
            --size 1280x720 --stats "$out/stats.json"
        echo "quickstart: frames written to $out/ (000001.png ...), statistics in $out/stats.json"
    elif [[ $status -ne 0 ]]; then
        exit $status
    fi
    ;;
test)
    install_missing "${BUILD_PKGS[@]}" "${TEST_PKGS[@]}"
    build
    prepare_demo
    # CI turns "no GL context" skips into failures: a green run must have rendered pixels.
    export KIOSK_REQUIRE_GL=${KIOSK_REQUIRE_GL:-1}
    ctest --test-dir "$BUILD" --output-on-failure -j "$JOBS" --timeout 600
    ;;
esac
