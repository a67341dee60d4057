#!/usr/bin/env bash
# Every test: install, build, then ctest (C++ unit tests, demo, consumer project against the
# installed CMake package), pytest (Python API, shading oracle, shadows, window, CLI, bench) and
# the sanitizer lane (the C++ tests again under AddressSanitizer + UndefinedBehaviorSanitizer,
# scripts/sanitize.sh) and the libFuzzer lane (the loaders' C++ fuzz targets built with clang,
# a short fixed-seed run of each: scripts/fuzz.sh). Vulkan validation layers are on throughout;
# any validation message, sanitizer or fuzzer finding fails the test.
set -euo pipefail
cd "$(dirname "$0")/.."
phase() { echo "test.sh: $1 done at ${SECONDS} s"; }  # where CI time goes
bash scripts/install-deps.sh
phase install-deps
bash scripts/build.sh
phase build
source scripts/env.sh
export WEFT_VALIDATION=1
ctest --test-dir build/py --output-on-failure --timeout 600
phase ctest
python3 -m pytest tests/python -q -p no:cacheprovider --durations=25
phase pytest
bash scripts/sanitize.sh
phase sanitize
bash scripts/fuzz.sh
phase fuzz
