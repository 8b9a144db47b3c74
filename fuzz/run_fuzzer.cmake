# Runs one fuzz target the way ctest does: over its seed corpus and its regression inputs
# (fuzz/regressions/<name>, the minimal inputs of what it once found), then a short run with a
# fixed seed, writing what it finds to a fresh folder. Fails on any finding.
#   cmake -DFUZZER=path/to/x_fuzzer -DNAME=x -DCORPORA=dir -DREGRESSIONS=dir -DWORK=dir
#         -DRUNS=n -P run_fuzzer.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/new)
set(inputs ${CORPORA}/${NAME})
if(IS_DIRECTORY ${REGRESSIONS}/${NAME})
  list(APPEND inputs ${REGRESSIONS}/${NAME})
endif()
execute_process(
  COMMAND ${FUZZER} -seed=1 -runs=${RUNS} -max_total_time=60 -timeout=10 -rss_limit_mb=2048
          -max_len=65536 -artifact_prefix=${WORK}/ ${WORK}/new ${inputs}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${NAME} fuzzer found a failure (exit ${status}); the input is in ${WORK}")
endif()
