# The subsystem targets of cpp/CMakeLists.txt (docs/design/ARCHITECTURE.md, "Layers").
#
#   weft_subsystem(<name> [DEPENDS <subsystems>] [HEADERS <public headers, no .h>]
#                  [SOURCES <extra sources>] [PUBLIC_LIBS <libs>] [LIBS <libs>])
#
# makes the OBJECT library weft_<name> from src/<name>/**.cpp. Subsystems are declared bottom up:
# DEPENDS may name only subsystems declared before, so the graph cannot have a cycle. The public
# headers stay together in include/weft/ (installed as one folder); HEADERS says which of them
# belong to <name>. Its include directory is a view, <build>/cpp/layers/<name>/, holding
#   <name>   -> src/<name>                (its private headers, #include "<name>/X.h")
#   weft/X.h -> include/weft/X.h          (its public headers, #include <weft/X.h>)
# and DEPENDS passes the views of the subsystems below on (PUBLIC), so a file compiles against
# exactly its own headers and those of the subsystems it depends on, directly or not.
set(WEFT_LAYER_VIEWS ${CMAKE_CURRENT_BINARY_DIR}/layers)
set(WEFT_SUBSYSTEMS "")
set(WEFT_LAYER_HEADERS "")

function(weft_subsystem name)
    cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "DEPENDS;HEADERS;SOURCES;PUBLIC_LIBS;LIBS")
    foreach(dep IN LISTS arg_DEPENDS)
        if(NOT dep IN_LIST WEFT_SUBSYSTEMS)
            message(FATAL_ERROR "weft_subsystem(${name}): '${dep}' is not a subsystem declared "
                                "before it (the layers are declared bottom up)")
        endif()
    endforeach()
    set(view ${WEFT_LAYER_VIEWS}/${name})
    file(REMOVE_RECURSE ${view}) # headers removed from HEADERS must leave the view
    file(MAKE_DIRECTORY ${view}/weft)
    file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/src/${name} ${view}/${name} SYMBOLIC)
    set(headers ${WEFT_LAYER_HEADERS})
    foreach(h IN LISTS arg_HEADERS)
        set(file ${CMAKE_CURRENT_SOURCE_DIR}/include/weft/${h}.h)
        if(NOT EXISTS ${file})
            message(FATAL_ERROR "weft_subsystem(${name}): no public header include/weft/${h}.h")
        endif()
        if(h IN_LIST headers)
            message(FATAL_ERROR "weft_subsystem(${name}): weft/${h}.h is already another "
                                "subsystem's")
        endif()
        list(APPEND headers ${h})
        file(CREATE_LINK ${file} ${view}/weft/${h}.h SYMBOLIC)
    endforeach()

    file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/${name}/*.cpp)
    add_library(weft_${name} OBJECT ${sources} ${arg_SOURCES})
    target_include_directories(weft_${name} PUBLIC $<BUILD_INTERFACE:${view}>)
    target_link_libraries(weft_${name} PUBLIC glm::glm ${arg_PUBLIC_LIBS} PRIVATE ${arg_LIBS})
    foreach(dep IN LISTS arg_DEPENDS)
        target_link_libraries(weft_${name} PUBLIC weft_${dep})
    endforeach()
    target_compile_features(weft_${name} PUBLIC cxx_std_17)
    target_compile_definitions(weft_${name} PRIVATE GLFW_INCLUDE_VULKAN
                               WEFT_VERSION="${PROJECT_VERSION}"
                               WEFT_HAVE_SHADERC=${WEFT_HAVE_SHADERC})
    if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
        target_compile_options(weft_${name} PRIVATE -Wall -Wextra -Wno-missing-field-initializers)
    endif()

    # Everything below it, for the link checks (object files link only where named directly).
    set(closure ${arg_DEPENDS})
    foreach(dep IN LISTS arg_DEPENDS)
        list(APPEND closure ${WEFT_LAYER_CLOSURE_${dep}})
    endforeach()
    list(REMOVE_DUPLICATES closure)
    set(WEFT_LAYER_CLOSURE_${name} ${closure} PARENT_SCOPE)
    list(APPEND WEFT_SUBSYSTEMS ${name})
    set(WEFT_SUBSYSTEMS ${WEFT_SUBSYSTEMS} PARENT_SCOPE)
    set(WEFT_LAYER_HEADERS ${headers} PARENT_SCOPE)
endfunction()

# Every public header belongs to exactly one subsystem (a new one must be given to one).
function(weft_check_public_headers dir)
    file(GLOB found RELATIVE ${dir} CONFIGURE_DEPENDS ${dir}/*.h)
    foreach(f IN LISTS found)
        string(REGEX REPLACE "\\.h$" "" h ${f})
        if(NOT h IN_LIST WEFT_LAYER_HEADERS)
            message(FATAL_ERROR "include/weft/${f} belongs to no subsystem: add it to the HEADERS "
                                "of one weft_subsystem() in cpp/CMakeLists.txt")
        endif()
    endforeach()
endfunction()

# One executable per subsystem made of its objects and those of everything below it and nothing
# else: a call into a subsystem above (a back-edge that compiles, e.g. through a declaration
# kept in a lower header) leaves an undefined symbol and fails the build.
function(weft_layer_link_checks)
    foreach(name IN LISTS WEFT_SUBSYSTEMS)
        add_executable(weft_layer_link_${name} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/LayerLinkCheck.cpp)
        target_link_libraries(weft_layer_link_${name} PRIVATE weft_${name})
        foreach(dep IN LISTS WEFT_LAYER_CLOSURE_${name})
            target_link_libraries(weft_layer_link_${name} PRIVATE weft_${dep})
        endforeach()
    endforeach()
endfunction()
