# Runs mmvPathTracerBenchmark and mmvPhysicalCalibration on one small scene
# and checks that each CSV has its header and the expected rows: one per
# scene, and one per swept setting (1 of ours, VTK Phong, 4 x 3 x 3 VTK
# scattering). Timings and errors are not checked.
file(REMOVE_RECURSE "${OUT}")
execute_process(
  COMMAND "${PATHTRACER}" --out "${OUT}" --size 16 --spp 2 --scenes orbital --verify
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "mmvPathTracerBenchmark exited with ${result}")
endif ()
file(STRINGS "${OUT}/pathtracer.csv" lines)
list(LENGTH lines count)
if (NOT count EQUAL 2)
  message(FATAL_ERROR "expected a header and 1 row in pathtracer.csv, got ${count} lines")
endif ()
execute_process(
  COMMAND "${CALIBRATION}" --out "${OUT}" --size 16 --truth-spp 4 --frames 1 --scenes orbital
    --s-scales 1 --ct-scales 1
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "mmvPhysicalCalibration exited with ${result}")
endif ()
file(STRINGS "${OUT}/physical_calibration.csv" lines)
list(LENGTH lines count)
if (NOT count EQUAL 39)
  message(FATAL_ERROR "expected a header and 38 rows in physical_calibration.csv, got ${count} lines")
endif ()
list(GET lines 0 header)
if (NOT header MATCHES "^scene,family,setting,frame_ms,rmse,")
  message(FATAL_ERROR "unexpected CSV header: ${header}")
endif ()
