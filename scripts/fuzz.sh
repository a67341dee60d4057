#!/usr/bin/env bash
# The libFuzzer lane (issue 13): the loaders and parsers built with clang-14 into build/fuzz
# (AddressSanitizer + UndefinedBehaviorSanitizer + libFuzzer coverage; only the subsystems the
# loaders live in, ccache shared with the other builds), then a short fixed-seed run of every
# target (ctest fuzz.*, tests/fuzz/cpp/CMakeLists.txt), any finding fatal.
#   bash scripts/fuzz.sh             build and run the short runs (part of scripts/test.sh)
#   bash scripts/fuzz.sh build       build only (build/fuzz/tests/fuzz/cpp/weft_fuzz_<target>)
#   bash scripts/fuzz.sh long [RUNS [TARGET...]]
#                                    long runs (BENCHMARKS.md, reliability): RUNS executions
#                                    (default 1000000, seed 7) of each target (default all), one
#                                    at a time under nice -n 15; the corpus each grows and its log
#                                    are in build/fuzz/long/<target>/, a summary in
#                                    build/fuzz/long-<target>.log
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
if [ "${1:-}" = long ]; then
    export WEFT_FUZZ_RUNS="${2:-1000000}" WEFT_FUZZ_SEED="${WEFT_FUZZ_SEED:-7}"
    export WEFT_FUZZ_OUT="$PWD/build/fuzz/long"
    shift $(($# < 2 ? $# : 2))
    targets=("$@")
    ((${#targets[@]})) || targets=(hair script jpeg gltf obj hdr png exr btfzip env btftree)
    status=0
    for t in "${targets[@]}"; do
        nice -n 15 ctest --test-dir build/fuzz --output-on-failure -V -R "^fuzz\.$t\$" \
            > "build/fuzz/long-$t.log" 2>&1 || status=1
        grep -E "^[0-9]+: (/|#[0-9]+[[:space:]]+DONE|Done|stat::)|Test +#" \
            "build/fuzz/long-$t.log" || true
    done
    exit $status
fi
ctest --test-dir build/fuzz --output-on-failure --timeout 300 -R '^fuzz\.'
echo "fuzz: every libFuzzer target ran clean"
