#!/usr/bin/env bash
# The sanitizer lane (issue 13): the library and its C++ tests built with AddressSanitizer and
# UndefinedBehaviorSanitizer into build/asan (ccache shared with the main build), then ctest
# with every finding fatal. Leaks inside Mesa's lavapipe/LLVM are suppressed by scripts/lsan.supp
# (each entry says why); nothing of weft's is. The tests that run Vulkan are run without leak
# detection: llvmpipe's JIT-compiled shaders allocate from code that has no symbols or module
# (LeakSanitizer reports "<unknown module>", which no suppression can name) -- ASan's memory
# errors and UBSan still apply to them.
#   bash scripts/sanitize.sh         build and run the tests (part of scripts/test.sh)
#   bash scripts/sanitize.sh build   build only (scripts/test.sh builds it while pytest runs)
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(cd .. && pwd)}"
launcher=()
if command -v ccache >/dev/null; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# -O1 -g1 (line tables: stack traces keep file:line) as ASan's documentation advises, instead of
# RelWithDebInfo's -O2 -g: a cold build takes 252 instead of 445 CPU-seconds (measured with
# CCACHE_DISABLE=1 on the 2-core VM), and the tests run as fast.
opt="-O1 -g1 -DNDEBUG"
cmake -S . -B build/asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWEFT_BUILD_TESTS=ON \
    -DWEFT_BUILD_PYTHON=OFF -DWEFT_BUILD_DEMO=OFF -DWEFT_BUILD_BENCH=OFF "${launcher[@]}" \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_C_FLAGS="$flags" \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$opt" -DCMAKE_C_FLAGS_RELWITHDEBINFO="$opt" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build build/asan --parallel "$(nproc)"
[ "${1:-}" = build ] && exit 0
source scripts/env.sh
export WEFT_VALIDATION=1
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
vulkan="RendererTest|OnTheGpu|HairScene.Frame|Validation\."
ctest --test-dir build/asan --output-on-failure --timeout 900 -E "consumer|demo|$vulkan"
ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" \
    ctest --test-dir build/asan --output-on-failure --timeout 900 -R "$vulkan"
echo "sanitize: ASan + UBSan clean"
