# Run by ctest (tests/CMakeLists.txt, layers.*): builds one probe target of the build tree and
# checks the outcome. EXPECT=fail: the compiler must stop at the planted #include of HEADER, not
# found in the subsystem's include view (so the layers, not a typo, stopped it). EXPECT=pass: the
# probe must build (the control: its includes are allowed).
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${TARGET}
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(EXPECT STREQUAL "fail")
    string(FIND "${out}" "${HEADER}: No such file or directory" at)
    if(result EQUAL 0 OR at EQUAL -1)
        message(FATAL_ERROR "${TARGET}: expected the compiler to miss ${HEADER} (exit ${result}):\n${out}")
    endif()
    message(STATUS "${TARGET}: ${HEADER} is not visible, as the layers require")
elseif(NOT result EQUAL 0)
    message(FATAL_ERROR "${TARGET}: the control probe should build (exit ${result}):\n${out}")
endif()
