# Runs mmvOpticalModelBenchmark on one tiny scene, one frame, and checks that
# the CSV has its header and one row per variant. Timings are not checked.
file(REMOVE_RECURSE "${OUT}")
execute_process(
  COMMAND "${BENCHMARK}" --out "${OUT}" --size 32 --frames 1 --scenes synthetic
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "mmvOpticalModelBenchmark exited with ${result}")
endif ()
file(STRINGS "${OUT}/optical_model.csv" lines)
list(LENGTH lines count)
if (NOT count EQUAL 7)
  message(FATAL_ERROR "expected a header and 6 rows in optical_model.csv, got ${count} lines")
endif ()
list(GET lines 0 header)
if (NOT header MATCHES "^scene,variant,anisotropy,emission,")
  message(FATAL_ERROR "unexpected CSV header: ${header}")
endif ()
