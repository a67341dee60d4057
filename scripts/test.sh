#!/usr/bin/env bash
# Every test: install, the formatting check (ruff: scripts/lint.sh), build, then ctest (C++ unit
# tests, demo, consumer project against the installed CMake package), pytest (Python API, shading oracle, shadows, window, CLI, bench) and
# the sanitizer lane (the C++ tests again under AddressSanitizer + UndefinedBehaviorSanitizer,
# scripts/sanitize.sh) and the libFuzzer lane (the loaders' C++ fuzz targets built with clang,
# a short fixed-seed run of each: scripts/fuzz.sh). Vulkan validation layers are on throughout;
# any validation message, sanitizer or fuzzer finding fails the test.
set -euo pipefail
cd "$(dirname "$0")/.."
phase() { echo "test.sh: $1 done at ${SECONDS} s"; }  # where CI time goes
bash scripts/install-deps.sh
phase install-deps
bash scripts/lint.sh
phase lint
bash scripts/build.sh
phase build
source scripts/env.sh
export WEFT_VALIDATION=1
# The sanitizer and fuzzer builds (two more builds of the library, the longest part of a run on a
# fresh machine) go on beside the tests at low priority: they take the CPU time pytest leaves
# idle (its single-threaded Python, its waits on subprocesses) and give way to it otherwise.
lanes_log=build/lanes-build.log
mkdir -p build
setsid nice -n 15 bash -c 'bash scripts/sanitize.sh build && bash scripts/fuzz.sh build' \
    > "$lanes_log" 2>&1 &
lanes=$!
trap 'kill -- -"$lanes" 2>/dev/null || true' EXIT  # a failed test stops the builds too
ctest --test-dir build/py --output-on-failure --timeout 600
phase ctest
# One pytest worker per core (pytest-xdist), each test file on one worker (its module fixtures,
# such as the path-traced references, are made once): pytest alone keeps ~1.1 of 2 cores busy,
# so the full suite took 549 s on one worker and 309 s on two (2-core VM, warm build).
python3 -m pytest tests/python -q -p no:cacheprovider -n auto --dist loadfile --durations=25
phase pytest
if ! wait "$lanes"; then
    tail -n 60 "$lanes_log"
    echo "test.sh: the sanitizer or fuzzer build failed (log: $lanes_log)" >&2
    exit 1
fi
phase "sanitizer and fuzzer builds (beside the tests)"
bash scripts/sanitize.sh
phase sanitize
bash scripts/fuzz.sh
phase fuzz
