# One short, reproducible libFuzzer run (ctest fuzz.<target>, see CMakeLists.txt): seed 1, RUNS
# executions over the corpora in CORPORA ('|'-separated; missing folders skipped) with inputs of
# at most MAX_LEN bytes; new inputs go to OUT/corpus, a crashing input to OUT/. Fails unless
# libFuzzer finishes all RUNS without a finding (crash, sanitizer report, leak, a 20 s input,
# 2 GiB of memory, or an exception other than weft::Error: FuzzCommon.h).
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT}/corpus)
string(REPLACE "|" ";" corpora "${CORPORA}")
set(dirs ${OUT}/corpus)
foreach(d IN LISTS corpora)
    if(IS_DIRECTORY ${d})
        list(APPEND dirs ${d})
    endif()
endforeach()
execute_process(COMMAND ${FUZZER} -seed=1 -runs=${RUNS} -max_len=${MAX_LEN} -timeout=20
                        -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix=${OUT}/ ${dirs}
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
message("${log}")
if(NOT rc EQUAL 0 OR NOT log MATCHES "Done ${RUNS} runs")
    message(FATAL_ERROR "${FUZZER}: a finding (exit ${rc}); the input is in ${OUT}/")
endif()
