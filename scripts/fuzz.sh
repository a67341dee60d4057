#!/usr/bin/env bash
# The libFuzzer lane (issue 13): the loaders and parsers built with clang-14 into build/fuzz
# (AddressSanitizer + UndefinedBehaviorSanitizer + libFuzzer coverage; only the subsystems the
# loaders live in, ccache shared with the other builds), then a short fixed-seed run of every
# target (ctest fuzz.*, tests/fuzz/cpp/CMakeLists.txt), any finding fatal.
#   bash scripts/fuzz.sh             build and run the short runs (part of scripts/test.sh)
#   bash scripts/fuzz.sh build       build only; the targets are build/fuzz/tests/fuzz/cpp/weft_fuzz_*
# A long run of one target: build/fuzz/tests/fuzz/cpp/weft_fuzz_hair -seed=7 -runs=1000000 \
#   NEW_CORPUS_DIR tests/fuzz/corpus/hair   (BENCHMARKS.md, reliability, has the commands run)
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(cd .. && pwd)}"
if ! command -v clang++-14 >/dev/null; then
    echo "fuzz: clang++-14 is missing (bash scripts/install-deps.sh installs clang-14 and" \
         "libclang-rt-14-dev)" >&2
    exit 1
fi
launcher=()
if command -v ccache >/dev/null; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B build/fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DWEFT_BUILD_FUZZERS=ON \
    -DWEFT_BUILD_TESTS=OFF -DWEFT_BUILD_PYTHON=OFF -DWEFT_BUILD_DEMO=OFF -DWEFT_BUILD_BENCH=OFF \
    "${launcher[@]}" >/dev/null
cmake --build build/fuzz --target weft_fuzzers --parallel "$(nproc)"
[ "${1:-}" = build ] && exit 0
ctest --test-dir build/fuzz --output-on-failure -R '^fuzz\.'
echo "fuzz: every libFuzzer target ran clean"
