#!/usr/bin/env bash
# gpu-check: on a machine with a Vulkan GPU, picks the GPU (never the CPU rasteriser lavapipe),
# runs weft's C++ tests and the GPU benchmark set (weft-bench) on it with the validation layers
# on, and writes gpu-check.json + gpu-check.md (and the benchmark's bench.json + bench.md) into
# the output folder. Needs only the native bundle (scripts/bundle.sh) and bash: no Python, no
# compiler, no development packages. In the source tree it uses build/py's binaries instead.
#
#   Vulkan loader: the system's libvulkan.so.1; the bundle's lib/fallback/ copy only when the
#     system has none (same for libstdc++ / libgcc_s when the system's are too old).
#   Validation: the system's Khronos layer, else the bundle's; if neither loads, the run says so
#     and goes on without validation.
#   No GPU: says so and exits 2, unless --allow-cpu (then it runs on lavapipe, for testing).
#
#   Timing: with validation on, the benchmark runs twice: once validated (any message fails it)
#     and once more without the layer, whose frame times are the figures to quote (the layer's
#     CPU work would otherwise be timed on a fast GPU); --no-timing-run leaves the second out.
#
# Usage: gpu-check.sh [--out DIR] [--allow-cpu] [--quick] [--device X] [--frames N] [--images]
#                     [--no-validation] [--no-timing-run]
# Exit: 0 all passed; 1 a test, the benchmark or validation failed; 2 no GPU (or bad usage).
set -uo pipefail

here=$(cd "$(dirname "$0")" && pwd)
out=gpu-check-out
allow_cpu=0
quick=0
device=""
validation=1
timing_run=1
bench_args=()
while (($#)); do
    case "$1" in
        --out) out=${2:?--out needs a folder}; shift 2 ;;
        --allow-cpu) allow_cpu=1; shift ;;
        --quick) quick=1; bench_args+=(--quick); shift ;;
        --device) device=${2:?--device needs an index or a name}; shift 2 ;;
        --frames) bench_args+=(--frames "${2:?--frames needs a number}"); shift 2 ;;
        --images) bench_args+=(--images); shift ;;
        --no-validation) validation=0; shift ;;
        --no-timing-run) timing_run=0; shift ;;
        -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; exit 0 ;;
        *) echo "gpu-check: unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
done

if [ -x "$here/bin/weft-bench" ]; then           # the unpacked bundle
    bundle=$here
    bench=$here/bin/weft-bench
    tests=$here/bin/weft_tests
elif [ -x "$here/../build/py/cpp/weft-bench" ]; then # the source tree after scripts/build.sh
    bundle=""
    bench=$here/../build/py/cpp/weft-bench
    tests=$here/../build/py/tests/weft_tests
else
    echo "gpu-check: no weft-bench next to this script (bin/) nor in build/py: unpack the bundle or run scripts/build.sh" >&2
    exit 2
fi
mkdir -p "$out" || exit 2
out=$(cd "$out" && pwd)
log=$out/gpu-check.log
: > "$log"
say() { echo "gpu-check: $*" | tee -a "$log" >&2; }

# Mesa's window-system code complains when XDG_RUNTIME_DIR is unset; give it a private one.
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "${XDG_RUNTIME_DIR}" ]; then
    export XDG_RUNTIME_DIR="${TMPDIR:-/tmp}/weft-xdg-$(id -u)"
    mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
fi

# 1. The loader and the C++ runtime: the system's first, the bundle's fallback only if needed.
loader=system
if ! err=$("$bench" --help 2>&1 >/dev/null); then
    echo "$err" >> "$log"
    missing=$(echo "$err" | grep -o '[A-Za-z0-9+_.-]*\.so\.[0-9]*' | sort -u | tr '\n' ' ' | sed 's/ $//')
    if [ -n "$bundle" ] && [ -d "$bundle/lib/fallback" ] &&
        LD_LIBRARY_PATH="$bundle/lib/fallback${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$bench" --help >/dev/null 2>>"$log"; then
        export LD_LIBRARY_PATH="$bundle/lib/fallback${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
        loader="the bundle's lib/fallback/ (the system's ${missing:-libraries} did not load)"
        say "using the bundle's fallback libraries: the system's ${missing:-libraries} did not load"
    else
        say "weft-bench does not start here: $err"
        exit 1
    fi
fi

# 2. The devices. A GPU is a discrete, integrated or virtual device; lavapipe reports "cpu".
list() { "$bench" --list-devices 2>>"$log"; }
devices=$(list)
list_rc=$?
# Containers often get NVIDIA's driver but not all of it where the loader looks: the ICD
# manifest missing, or present while the driver's libraries sit outside the linker's path
# (/usr/local/nvidia/lib64): then Vulkan sees no GPU (or fails with INCOMPATIBLE_DRIVER) although
# nvidia-smi does. Try the manifests the driver installed with its library folder on the path,
# else write a manifest (what the driver installs as nvidia_icd.json) into the output folder.
icd_note=""
has_gpu() { awk -F'\t' '$1 == "device" && $3 != "cpu"' | grep -q .; }
if { ((list_rc != 0)) || ! echo "$devices" | has_gpu; } &&
    command -v nvidia-smi >/dev/null 2>&1 && nvidia-smi -L >/dev/null 2>&1; then
    nv_libs=""
    for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
        [ -d "$d" ] && nv_libs=${nv_libs:+$nv_libs:}$d
    done
    # use_icd MANIFEST NOTE: keeps MANIFEST (and the driver's library folders) when the devices
    # listed through it include a GPU
    use_icd() {
        local more
        more=$(LD_LIBRARY_PATH="$nv_libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
               VK_ICD_FILENAMES="$1" VK_DRIVER_FILES="$1" list) && echo "$more" | has_gpu || return 1
        export VK_ICD_FILENAMES="$1" VK_DRIVER_FILES="$1"
        [ -n "$nv_libs" ] && export LD_LIBRARY_PATH="$nv_libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
        devices=$more
        list_rc=0
        icd_note=$2
        say "$icd_note"
    }
    for manifest in /usr/local/nvidia/share/vulkan/icd.d/*.json /usr/local/nvidia/etc/vulkan/icd.d/*.json \
                    /usr/share/vulkan/icd.d/nvidia*.json /etc/vulkan/icd.d/nvidia*.json; do
        [ -f "$manifest" ] &&
            use_icd "$manifest" "the loader did not find NVIDIA's Vulkan ICD manifest: using $manifest" &&
            break
    done
    [ -z "$icd_note" ] &&
    for lib in libGLX_nvidia.so.0 libEGL_nvidia.so.0; do
        ldconfig -p 2>/dev/null | grep -q "$lib" ||
            for d in ${nv_libs//:/ }; do [ -e "$d/$lib" ] && break; false; done || continue
        printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "%s", "api_version": "1.3"}}\n' \
            "$lib" > "$out/nvidia_icd.json"
        use_icd "$out/nvidia_icd.json" \
            "NVIDIA's Vulkan ICD manifest was missing: wrote $out/nvidia_icd.json ($lib)" && break
    done
    [ -z "$icd_note" ] && say "nvidia-smi sees a GPU but Vulkan does not, and no NVIDIA ICD library (libGLX_nvidia.so.0 / libEGL_nvidia.so.0) loads: the driver's Vulkan part is missing here"
fi
if ((list_rc != 0)); then
    say "Vulkan is not usable here (no driver / ICD?):"
    tail -n 3 "$log" >&2
    exit 2
fi
echo "$devices" > "$out/devices.txt"
pick=""
for type in discrete integrated virtual; do
    pick=$(echo "$devices" | awk -F'\t' -v t="$type" '$1 == "device" && $3 == t {print $2; exit}')
    [ -n "$pick" ] && break
done
gpu=1
if [ -n "$device" ]; then
    pick=$device
elif [ -z "$pick" ]; then
    gpu=0
    names=$(echo "$devices" | awk -F'\t' '$1 == "device" {printf "%s%s (%s)", sep, $4, $3; sep = ", "}')
    if ((allow_cpu)); then
        say "NO GPU: the only Vulkan device(s): ${names:-none}. --allow-cpu: running on the CPU rasteriser; these are not GPU figures."
        pick=$(echo "$devices" | awk -F'\t' '$1 == "device" {print $2; exit}')
    else
        say "NO GPU: the only Vulkan device(s): ${names:-none}. Nothing measured (use --allow-cpu to run on the CPU rasteriser anyway)."
        exit 2
    fi
fi
export WEFT_DEVICE=$pick
chosen=$(WEFT_DEVICE=$pick list | awk -F'\t' '$1 == "device" && $7 == "chosen"')
dev_name=$(echo "$chosen" | cut -f4)
dev_type=$(echo "$chosen" | cut -f3)
dev_api=$(echo "$chosen" | cut -f5)
dev_driver=$(echo "$chosen" | cut -f6)
[ -n "$dev_name" ] || { say "WEFT_DEVICE=$pick matches no usable device"; exit 2; }
say "device $pick: $dev_name ($dev_type, Vulkan $dev_api, driver $dev_driver); loader: $loader"
# The GPU's own report of itself, where its tool exists (name, driver, memory, clocks).
gpu_info=""
if command -v nvidia-smi >/dev/null 2>&1; then
    gpu_info=$(nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm,power.limit \
                          --format=csv,noheader 2>/dev/null | head -4 | tr '\n' ';' | sed 's/;$//')
elif command -v rocm-smi >/dev/null 2>&1; then
    gpu_info=$(rocm-smi --showproductname --showdriverversion 2>/dev/null | grep -v '^=' | tr -s ' \n' ' ')
fi
[ -n "$gpu_info" ] && say "GPU tool: $gpu_info"

# 3. Validation: the system's layer, else the bundle's, else none (said, and the run goes on).
validation_note=off
if ((validation)); then
    if echo "$devices" | grep -q $'^validation\tinstalled'; then
        validation_note="on (system layer)"
    elif [ -n "$bundle" ] && [ -f "$bundle/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json" ] &&
        VK_LAYER_PATH="$bundle/share/vulkan/explicit_layer.d" "$bench" --list-devices 2>>"$log" |
            grep -q $'^validation\tinstalled'; then
        export VK_LAYER_PATH="$bundle/share/vulkan/explicit_layer.d"
        validation_note="on (the bundle's layer: the system has none)"
    else
        validation=0
        validation_note="off: no Khronos validation layer loads here (install vulkan-validationlayers / the Vulkan SDK's)"
        say "VALIDATION LAYERS NOT AVAILABLE: running without validation"
    fi
fi
export WEFT_VALIDATION=$validation
say "validation: $validation_note"

# 4. The C++ tests, on the chosen device, in a scratch folder (some write files).
mkdir -p "$out/tests-work"
start=$(date +%s)
(cd "$out/tests-work" && "$tests" --gtest_brief=1 --gtest_output="json:$out/tests.json") > "$out/tests.log" 2>&1
tests_rc=$?
tests_s=$(($(date +%s) - start))
tests_passed=$(sed -n 's/.*\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$out/tests.log" | tail -1)
tests_failed=$(sed -n 's/.*\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$out/tests.log" | tail -1)
tests_skipped=$(sed -n 's/.*\[  SKIPPED \] \([0-9]*\) test.*/\1/p' "$out/tests.log" | tail -1)
say "C++ tests: ${tests_passed:-0} passed, ${tests_failed:-0} failed, ${tests_skipped:-0} skipped (exit $tests_rc, ${tests_s} s)"

# 5. The benchmark set.
start=$(date +%s)
"$bench" "${bench_args[@]}" --out "$out/bench" 2> >(tee -a "$log" >&2)
bench_rc=$?
bench_s=$(($(date +%s) - start))
say "benchmark: exit $bench_rc (${bench_s} s), $out/bench/bench.md"
timing_rc=0
timing_s=0
if ((validation && timing_run && bench_rc == 0)); then
    start=$(date +%s)
    WEFT_VALIDATION=0 "$bench" "${bench_args[@]}" --out "$out/bench-timing" 2> >(tee -a "$log" >&2)
    timing_rc=$?
    timing_s=$(($(date +%s) - start))
    say "benchmark without the validation layer (the timings): exit $timing_rc (${timing_s} s), $out/bench-timing/bench.md"
fi

# 6. The summary, JSON and Markdown, written with the shell alone (no Python on the machine).
esc() { printf '%s' "$1" | sed 's/\\/\\\\/g; s/"/\\"/g' | tr -d '\000-\037'; }
status=passed
((tests_rc == 0 && bench_rc == 0 && timing_rc == 0)) || status=failed
cat > "$out/gpu-check.json" <<EOF
{"status": "$status", "gpu": $( ((gpu)) && echo true || echo false), "date": "$(date -u +%Y-%m-%dT%H:%M:%SZ)",
 "host": "$(esc "$(uname -srm)")", "cpu": "$(esc "$(awk -F': ' '/^model name/ {print $2; exit}' /proc/cpuinfo)")",
 "device": {"index": "$(esc "$pick")", "name": "$(esc "$dev_name")", "type": "$(esc "$dev_type")",
            "api_version": "$(esc "$dev_api")", "driver": "$(esc "$dev_driver")"},
 "gpu_tool": "$(esc "$gpu_info")", "icd": "$(esc "$icd_note")", "loader": "$(esc "$loader")", "validation": "$(esc "$validation_note")",
 "tests": {"exit": $tests_rc, "passed": ${tests_passed:-0}, "failed": ${tests_failed:-0},
           "skipped": ${tests_skipped:-0}, "seconds": $tests_s, "log": "tests.log"},
 "bench": {"exit": $bench_rc, "seconds": $bench_s, "json": "bench/bench.json", "markdown": "bench/bench.md"},
 "timing": {"ran": $([ -f "$out/bench-timing/bench.json" ] && echo true || echo false), "exit": $timing_rc, "seconds": $timing_s,
            "json": "bench-timing/bench.json", "markdown": "bench-timing/bench.md"}}
EOF
{
    echo "# weft gpu-check: $status"
    echo
    ((gpu)) || echo "**No GPU on this machine: these figures are from the CPU rasteriser (--allow-cpu).**"
    ((gpu)) || echo
    echo "- device $pick: **$dev_name** ($dev_type, Vulkan $dev_api, driver $dev_driver)"
    [ -n "$gpu_info" ] && echo "- GPU (vendor tool): $gpu_info"
    echo "- Vulkan loader: $loader; validation: $validation_note"
    echo "- host: $(uname -srm); $(awk -F': ' '/^model name/ {print $2; exit}' /proc/cpuinfo)"
    echo "- C++ tests: ${tests_passed:-0} passed, ${tests_failed:-0} failed, ${tests_skipped:-0} skipped (exit $tests_rc, ${tests_s} s)"
    echo "- benchmark (validation $validation_note): exit $bench_rc, ${bench_s} s"
    if [ -f "$out/bench-timing/bench.md" ]; then
        echo "- benchmark without the validation layer: exit $timing_rc, ${timing_s} s; its tables follow"
        echo "  (the validated run's are in bench/bench.md)"
        echo
        sed 's/^#/##/' "$out/bench-timing/bench.md"
    else
        echo
        [ -f "$out/bench/bench.md" ] && sed 's/^#/##/' "$out/bench/bench.md"
    fi
} > "$out/gpu-check.md"
say "$status: $out/gpu-check.md"
[ "$status" = passed ] || exit 1
exit 0
