# libzip and the static shaderc/glslang/SPIRV-Tools libraries as imported targets weft::zip and
# weft::shaderc, found by name on the machine that configures: used to build weft and, installed
# beside weftConfig.cmake, by projects that link the installed (static) weft -- so the exported
# targets name weft::zip / weft::shaderc instead of absolute paths of the build machine.
# Neither is found through its own CMake package: Debian's libzip package refers to tools of
# libzip-tools and fails without them, and libshaderc.so carries a partial glslang that clashes
# with the static one, so weft links shaderc_combined.a with the static glslang and SPIRV-Tools
# libraries it was built against, in dependency order.
if(NOT TARGET weft::zip)
    find_path(WEFT_LIBZIP_INCLUDE_DIR zip.h REQUIRED)
    find_library(WEFT_LIBZIP_LIBRARY zip REQUIRED)
    add_library(weft::zip UNKNOWN IMPORTED)
    set_target_properties(weft::zip PROPERTIES IMPORTED_LOCATION "${WEFT_LIBZIP_LIBRARY}"
                          INTERFACE_INCLUDE_DIRECTORIES "${WEFT_LIBZIP_INCLUDE_DIR}")
endif()

if(NOT TARGET weft::shaderc)
    find_path(WEFT_SHADERC_INCLUDE_DIR shaderc/shaderc.h)
    find_library(WEFT_SHADERC_LIBRARY NAMES libshaderc_combined.a shaderc_combined)
    set(WEFT_SHADERC_LIBRARIES "")
    if(WEFT_SHADERC_INCLUDE_DIR AND WEFT_SHADERC_LIBRARY)
        set(WEFT_SHADERC_LIBRARIES ${WEFT_SHADERC_LIBRARY})
        foreach(lib glslang SPIRV MachineIndependent OSDependent GenericCodeGen OGLCompiler HLSL
                    glslang-default-resource-limits SPIRV-Tools-opt SPIRV-Tools)
            find_library(WEFT_SHADERC_DEP_${lib} NAMES ${lib})
            if(WEFT_SHADERC_DEP_${lib})
                list(APPEND WEFT_SHADERC_LIBRARIES ${WEFT_SHADERC_DEP_${lib}})
            endif()
        endforeach()
        add_library(weft::shaderc INTERFACE IMPORTED)
        set_target_properties(weft::shaderc PROPERTIES
                              INTERFACE_LINK_LIBRARIES "${WEFT_SHADERC_LIBRARIES}"
                              INTERFACE_INCLUDE_DIRECTORIES "${WEFT_SHADERC_INCLUDE_DIR}")
    endif()
endif()
