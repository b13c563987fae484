#!/bin/sh
# Re-generate every golden image from the current renderer (llvmpipe) and show what changed.
# Review the PNG diffs before committing: a golden is a claim that the picture is right.
set -eu
cd "$(dirname "$0")/../.."
BUILD=${1:-build}
KIOSK_UPDATE_GOLDEN=1 ctest --test-dir "$BUILD" -L 'gl|render|scenario' --output-on-failure
git status --short tests/golden
