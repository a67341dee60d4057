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

# libshaderc (runtime shader compilation for hot reload) is optional: libshaderc-dev. Linked by
# path, which also travels into the installed CMake package unchanged.
# Debian's libshaderc.so carries its own partial glslang that clashes with the static glslang,
# so weft links shaderc_combined.a with the static glslang (glslang-dev) and SPIRV-Tools
# libraries it was built against, in dependency order.
find_path(WEFT_SHADERC_INCLUDE_DIR shaderc/shaderc.h)
find_library(WEFT_SHADERC_LIBRARY NAMES libshaderc_combined.a shaderc_combined)
set(WEFT_SHADERC_LIBRARIES ${WEFT_SHADERC_LIBRARY})
foreach(lib glslang SPIRV MachineIndependent OSDependent GenericCodeGen OGLCompiler HLSL
            glslang-default-resource-limits SPIRV-Tools-opt SPIRV-Tools)
    find_library(WEFT_SHADERC_DEP_${lib} NAMES ${lib})
    if(WEFT_SHADERC_DEP_${lib})
        list(APPEND WEFT_SHADERC_LIBRARIES ${WEFT_SHADERC_DEP_${lib}})
    endif()
endforeach()
if(WEFT_HOT_RELOAD AND WEFT_SHADERC_INCLUDE_DIR AND WEFT_SHADERC_LIBRARY)
    set(WEFT_HAVE_SHADERC 1)
else()
    set(WEFT_HAVE_SHADERC 0)
endif()

# Ceres is optional; the BTF fitter falls back to its own Levenberg-Marquardt without it.
find_package(Ceres QUIET)
set(WEFT_HAVE_CERES ${Ceres_FOUND})
