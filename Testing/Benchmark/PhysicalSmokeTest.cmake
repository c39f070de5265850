# Runs mmvPathTracerBenchmark and mmvPhysicalCalibration on one small scene
# (and mmvMediumCalibration on one medium, below)
# and checks that each CSV has its header and the expected rows: one per
# scene, and one per swept setting (1 of ours and 1 of ours with its
# exposure fitted, VTK Phong, 4 x 3 x 3 VTK scattering; black background).
# Timings and errors are not checked.
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
    --s-scales 1 --ct-scales 1 --fit-exposure --black-background
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "mmvPhysicalCalibration exited with ${result}")
endif ()
file(STRINGS "${OUT}/physical_calibration.csv" lines)
list(LENGTH lines count)
if (NOT count EQUAL 40)
  message(FATAL_ERROR "expected a header and 39 rows in physical_calibration.csv, got ${count} lines")
endif ()
if (NOT lines MATCHES ",ours-exposure,s_scale=1 ct_scale=1 ka_scale=")
  message(FATAL_ERROR "no ours-exposure row in physical_calibration.csv")
endif ()
list(GET lines 0 header)
if (NOT header MATCHES "^scene,family,setting,frame_ms,rmse,")
  message(FATAL_ERROR "unexpected CSV header: ${header}")
endif ()
# mmvMediumCalibration on one medium and a 2 x 1 grid: a header and one row
# per family (default, fit, mapped, VTK) and per grid point; a second run
# reads the cached truth.
foreach (pass IN ITEMS render cached)
  execute_process(
    COMMAND "${MEDIUM}" --out "${OUT}/medium" --size 16 --truth-spp 4 --frames 1 --albedos 0.6
      --anisotropies 0.3 --depths 4 --s-values 0,4 --ct-values 1
    RESULT_VARIABLE result)
  if (NOT result EQUAL 0)
    message(FATAL_ERROR "mmvMediumCalibration (${pass}) exited with ${result}")
  endif ()
endforeach ()
file(GLOB cached "${OUT}/medium/truth-cache/*.vti")
list(LENGTH cached count)
if (NOT count EQUAL 1)
  message(FATAL_ERROR "expected 1 cached truth, found ${count}")
endif ()
file(STRINGS "${OUT}/medium/medium_calibration.csv" lines)
list(LENGTH lines count)
if (NOT count EQUAL 5)
  message(FATAL_ERROR "expected a header and 4 rows in medium_calibration.csv, got ${count} lines")
endif ()
# The same medium in a cube (--shape): its own truth, four rows.
execute_process(
  COMMAND "${MEDIUM}" --out "${OUT}/cube" --size 16 --truth-spp 4 --frames 1 --albedos 0.6
    --anisotropies 0.3 --depths 4 --s-values 0,4 --ct-values 1 --shape cube
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "mmvMediumCalibration --shape cube exited with ${result}")
endif ()
file(STRINGS "${OUT}/cube/medium_calibration.csv" lines)
list(LENGTH lines count)
if (NOT count EQUAL 5 OR NOT lines MATCHES ",cube")
  message(FATAL_ERROR "expected a header and 4 cube rows, got ${count} lines")
endif ()
file(STRINGS "${OUT}/medium/medium_fit_grid.csv" lines)
list(LENGTH lines count)
if (NOT count EQUAL 3)
  message(FATAL_ERROR "expected a header and 2 rows in medium_fit_grid.csv, got ${count} lines")
endif ()
