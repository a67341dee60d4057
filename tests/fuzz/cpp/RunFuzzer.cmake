# One libFuzzer run (ctest fuzz.<target>, see CMakeLists.txt): RUNS executions (seed 1) over the
# corpora in CORPORA ('|'-separated; missing folders skipped) with inputs of at most MAX_LEN
# bytes. New inputs go to OUT/corpus, a crashing input to OUT/, the whole log to OUT/fuzz.log.
# Fails unless libFuzzer finishes all RUNS without a finding (crash, sanitizer report, leak, an
# input running 20 s, 2 GiB of memory, or an exception other than weft::Error: FuzzCommon.h).
# WEFT_FUZZ_RUNS and WEFT_FUZZ_SEED in the environment replace RUNS and the seed, WEFT_FUZZ_OUT
# the folder of OUT (OUT becomes $WEFT_FUZZ_OUT/NAME), for long runs beside the short ones.
if(DEFINED ENV{WEFT_FUZZ_RUNS})
    set(RUNS $ENV{WEFT_FUZZ_RUNS})
endif()
if(DEFINED ENV{WEFT_FUZZ_OUT})
    set(OUT $ENV{WEFT_FUZZ_OUT}/${NAME})
endif()
set(seed 1)
if(DEFINED ENV{WEFT_FUZZ_SEED})
    set(seed $ENV{WEFT_FUZZ_SEED})
endif()
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT}/corpus)
string(REPLACE "|" ";" corpora "${CORPORA}")
set(dirs ${OUT}/corpus)
foreach(d IN LISTS corpora)
    if(IS_DIRECTORY ${d})
        list(APPEND dirs ${d})
    endif()
endforeach()
set(command ${FUZZER} -seed=${seed} -runs=${RUNS} -max_len=${MAX_LEN} -timeout=20
            -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix=${OUT}/ ${dirs})
string(REPLACE ";" " " shown "${command}")
message("${shown}")
execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_FILE ${OUT}/fuzz.log
                ERROR_FILE ${OUT}/fuzz.log)
# The summary lines (fuzzed bytes elsewhere in the log may hold '[' or ';', which CMake lists
# would not keep apart, so the log is filtered by regex and otherwise read as one string)
file(STRINGS ${OUT}/fuzz.log summary
     REGEX "^(#[0-9]+[ \t]+(INITED|DONE)|Done [0-9]+ runs|stat::)")
string(REPLACE ";" "\n" summary "${summary}")
if(NOT rc EQUAL 0 OR NOT summary MATCHES "Done ${RUNS} runs")
    file(READ ${OUT}/fuzz.log log)
    string(LENGTH "${log}" n)
    if(n GREATER 6000)
        math(EXPR first "${n} - 6000")
        string(SUBSTRING "${log}" ${first} 6000 log)
    endif()
    message(FATAL_ERROR "${log}\n${FUZZER}: a finding (exit ${rc}); the input is in ${OUT}/, "
                        "the log in ${OUT}/fuzz.log")
endif()
message("${summary}")
