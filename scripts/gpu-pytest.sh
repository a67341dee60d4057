#!/usr/bin/env bash
# The Python tests on a GPU machine, after gpu-check.sh (BENCHMARKS.md, gpu): in the source tree,
# with the wheel `scripts/bundle.sh --python PY` made for that machine's python3 and the Vulkan
# setup gpu-check chose there (the bundle's fallback loader when the system has none, the ICD
# manifest it found or wrote, the bundle's validation layer when the system has none). The
# wheel goes into a scratch folder with pip --target (no package index needed); numpy, pytest
# and pytest-xdist must be the machine's. Runs `pytest tests/python -m "not slow"` with
# validation on and writes pytest.log and pytest.xml into the output folder.
#
# Usage: scripts/gpu-pytest.sh --bundle DIR --wheel FILE [--check-out DIR] [--out DIR]
#                              [--workers N] [--tests PATH] [-- more pytest arguments]
# Exit: pytest's (0 all passed), 2 bad usage or no usable wheel.
set -uo pipefail
cd "$(dirname "$0")/.."
bundle="" wheel="" check="" out=gpu-pytest-out workers=8 tests=tests/python
extra=()
while (($#)); do
    case "$1" in
        --bundle) bundle=${2:?--bundle needs the unpacked bundle}; shift 2 ;;
        --wheel) wheel=${2:?--wheel needs a .whl}; shift 2 ;;
        --check-out) check=${2:?--check-out needs the output folder of gpu-check}; shift 2 ;;
        --out) out=${2:?--out needs a folder}; shift 2 ;;
        --workers) workers=${2:?--workers needs a number}; shift 2 ;;
        --tests) tests=${2:?--tests needs a path}; shift 2 ;;
        --) shift; extra=("$@"); break ;;
        -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; exit 0 ;;
        *) echo "gpu-pytest: unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
done
[ -f "$wheel" ] || { echo "gpu-pytest: no wheel '$wheel' (scripts/bundle.sh --python PY)" >&2; exit 2; }
[ -d "$bundle/lib" ] || { echo "gpu-pytest: '$bundle' is not an unpacked bundle" >&2; exit 2; }
mkdir -p "$out" && out=$(cd "$out" && pwd)
# the Vulkan setup gpu-check used: its manifest (found or written) and the driver's libraries
if [ -n "$check" ] && [ -f "$check/gpu-check.log" ]; then
    icd=$(sed -n 's/.*\(using\|wrote\) \(\/[^ ]*\.json\).*/\2/p' "$check/gpu-check.log" | head -1)
    if [ -n "$icd" ]; then
        export VK_ICD_FILENAMES=$icd VK_DRIVER_FILES=$icd
        for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
            [ -d "$d" ] && export LD_LIBRARY_PATH=$d${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
        done
    fi
fi
ldconfig -p 2>/dev/null | grep -q 'libvulkan\.so\.1 ' ||
    export LD_LIBRARY_PATH=$bundle/lib/fallback${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
layers=$bundle/share/vulkan/explicit_layer.d
ls /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json >/dev/null 2>&1 ||
    { [ -d "$layers" ] && export VK_LAYER_PATH=$layers; }
site=$(mktemp -d "${TMPDIR:-/tmp}/weft-gpu-pytest.XXXXXX")
trap 'rm -rf "$site"' EXIT
python3 -m pip install -q --no-index --no-deps --no-compile --target "$site" "$wheel" ||
    { echo "gpu-pytest: pip could not install $wheel for $(python3 --version 2>&1)" >&2; exit 2; }
export PYTHONPATH=$site WEFT_VALIDATION=1 PYTHONUNBUFFERED=1
python3 -c 'import weft; print("gpu-pytest: weft from", weft.__file__, "on",
                               [d["name"] for d in weft.devices() if d["selected"]])'
python3 -m pytest "$tests" -m "not slow" -q -p no:cacheprovider -n "$workers" -rfE \
    --junitxml="$out/pytest.xml" "${extra[@]}" 2>&1 | tee "$out/pytest.log" | tail -15
exit "${PIPESTATUS[0]}"
