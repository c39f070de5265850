# Runs mmvBenchmark on one small scene with two methods and checks that the
# CSV has its header and one row per method. Timings are not checked.
file(REMOVE_RECURSE "${OUT}")
execute_process(
  COMMAND "${BENCHMARK}" --out "${OUT}" --size 32 --frames 1 --light-frames 1
    --scenes synthetic --quick
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "mmvBenchmark exited with ${result}")
endif ()
file(STRINGS "${OUT}/benchmark.csv" lines)
list(LENGTH lines count)
if (NOT count EQUAL 3)
  message(FATAL_ERROR "expected a header and 2 rows in benchmark.csv, got ${count} lines")
endif ()
list(GET lines 0 header)
if (NOT header MATCHES "^scene,method,family,")
  message(FATAL_ERROR "unexpected CSV header: ${header}")
endif ()
