# Finds weft's system dependencies (Debian packages); no third-party source lives in this repo.
#   Vulkan  : libvulkan-dev (+ mesa-vulkan-drivers for lavapipe, vulkan-validationlayers)
#   glslc   : glslc (shaders -> SPIR-V at build time)
#   glfw3   : libglfw3-dev      glm : libglm-dev      PNG : libpng-dev
#   OpenEXR : libopenexr-dev (float images)
#   GTest   : libgtest-dev (tests only)               Ceres: libceres-dev (optional)
#   JPEG    : libjpeg62-turbo-dev                     libzip: libzip-dev (BTF datasets)
#   TinyGLTF: libtinygltf-dev (glTF 2.0 meshes)       CLI11 : libcli11-dev (the demo's options)
#   nlohmann_json: nlohmann-json3-dev (the demo's JSON stats)
#   tinyobjloader: libtinyobjloader-dev (OBJ + MTL meshes)
#   stb     : libstb-dev (.hdr images: the headers, compiled in cpp/src/core/ImageHdr.cpp)
#   imgui   : libimgui-dev (+ libstb's library; the demo's panel, optional: cpp/CMakeLists.txt)
find_package(Vulkan REQUIRED)
find_package(glfw3 3.3 REQUIRED)
find_package(glm REQUIRED)
find_package(PNG REQUIRED)
find_package(OpenEXR CONFIG REQUIRED)
find_package(JPEG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(tinyobjloader CONFIG REQUIRED)
find_path(WEFT_STB_INCLUDE_DIR stb_image.h PATH_SUFFIXES stb REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json 3 CONFIG REQUIRED)
# libzip and shaderc (optional: runtime shader compilation for hot reload, libshaderc-dev) as
# imported targets: cpp/cmake/weftSystemLibs.cmake, also installed for consumers.
include(${PROJECT_SOURCE_DIR}/cpp/cmake/weftSystemLibs.cmake)
find_package(Threads REQUIRED)

find_program(WEFT_GLSLC glslc REQUIRED)

if(WEFT_HOT_RELOAD AND TARGET weft::shaderc)
    set(WEFT_HAVE_SHADERC 1)
else()
    set(WEFT_HAVE_SHADERC 0)
endif()

# Ceres is optional; the BTF fitter falls back to its own Levenberg-Marquardt without it.
find_package(Ceres QUIET)
set(WEFT_HAVE_CERES ${Ceres_FOUND})
