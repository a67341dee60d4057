# Finds weft's system dependencies (Debian packages); no third-party source lives in this repo.
#   Vulkan  : libvulkan-dev (+ mesa-vulkan-drivers for lavapipe, vulkan-validationlayers)
#   glslc   : glslc (shaders -> SPIR-V at build time)
#   glfw3   : libglfw3-dev      glm : libglm-dev      PNG : libpng-dev
#   OpenEXR : libopenexr-dev (float images)
#   GTest   : libgtest-dev (tests only)               Ceres: libceres-dev (optional)
#   JPEG    : libjpeg62-turbo-dev                     libzip: libzip-dev (BTF datasets)
find_package(Vulkan REQUIRED)
find_package(glfw3 3.3 REQUIRED)
find_package(glm REQUIRED)
find_package(PNG REQUIRED)
find_package(OpenEXR CONFIG REQUIRED)
find_package(JPEG REQUIRED)
# libzip by path: Debian's libzip CMake package refers to tools of libzip-tools and fails without
# them; a plain library path also travels into the installed weft package unchanged.
find_path(WEFT_LIBZIP_INCLUDE_DIR zip.h REQUIRED)
find_library(WEFT_LIBZIP_LIBRARY zip REQUIRED)
find_package(Threads REQUIRED)

find_program(WEFT_GLSLC glslc REQUIRED)

# shaderc (runtime shader compilation for hot reload) is optional.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
    pkg_check_modules(WEFT_SHADERC QUIET IMPORTED_TARGET shaderc)
endif()

# Ceres is optional; the BTF fitter falls back to its own Levenberg-Marquardt without it.
find_package(Ceres QUIET)
set(WEFT_HAVE_CERES ${Ceres_FOUND})
