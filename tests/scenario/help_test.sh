#!/usr/bin/env bash
# `--help` (and -h) on every command and subcommand prints its usage on stdout and exits 0
# (docs/cli.md), and an unknown GEOKIOSK_LOG value is warned about exactly once.
#   help_test.sh GEOKIOSK
set -u
GK=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0

check_help() {
    "$GK" "$@" >"$tmp/out" 2>"$tmp/err"
    local got=$?
    if [[ $got -ne 0 ]]; then
        echo "FAIL: geokiosk $* -> exit $got, want 0"; sed 's/^/    /' "$tmp/err" | head -3
        fail=$((fail + 1)); return
    fi
    if ! grep -q "usage: geokiosk" "$tmp/out"; then
        echo "FAIL: geokiosk $* -> no usage on stdout"; fail=$((fail + 1)); return
    fi
    echo "ok:   geokiosk $*"; pass=$((pass + 1))
}

for flag in --help -h; do
    check_help $flag
    check_help play $flag
    check_help render $flag
    check_help validate $flag
    check_help info $flag
    check_help import $flag
    check_help import elevation $flag
    check_help import imagery $flag
    check_help import sequence $flag
    check_help import topographic $flag
    check_help import breaklines $flag
    check_help import model-mesh $flag
    check_help import textures $flag
done
# --help wins over other (even wrong) arguments, as with GNU tools.
check_help render scenarios/none.json --help
check_help import elevation --help --store x.gpkg

GEOKIOSK_LOG=loud "$GK" info /nonexistent.gpkg >"$tmp/out" 2>"$tmp/err"
n=$(grep -c "GEOKIOSK_LOG" "$tmp/err")
if [[ $n -eq 1 ]] && grep -q "debug, info, warn, error" "$tmp/err"; then
    echo "ok:   unknown GEOKIOSK_LOG warned once"; pass=$((pass + 1))
else
    echo "FAIL: unknown GEOKIOSK_LOG warned $n times"; sed 's/^/    /' "$tmp/err" | head -3
    fail=$((fail + 1))
fi
GEOKIOSK_LOG=warn "$GK" info /nonexistent.gpkg >"$tmp/out" 2>"$tmp/err"
if grep -q "GEOKIOSK_LOG" "$tmp/err"; then
    echo "FAIL: a valid GEOKIOSK_LOG was warned about"; fail=$((fail + 1))
else
    echo "ok:   valid GEOKIOSK_LOG is silent"; pass=$((pass + 1))
fi
echo "$pass passed, $fail failed"
[[ $fail -eq 0 ]]
