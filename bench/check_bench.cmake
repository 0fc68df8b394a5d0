# cmake -D EXE=<benchmark program> [-D EMULATOR=a|b|c] -P bench/check_bench.cmake
# Runs every benchmark of a Google Benchmark program once (the shortest minimum time) and fails
# when one reports an error: the edge benchmarks check their outputs (windowed blobs equal the
# full frame's, the masks equal the reference's) and call SkipWithError otherwise, which
# leaves the program's exit status 0. ctest runs this for bench_edge_blobs and bench_edge_mask,
# natively (label unit) and under qemu-aarch64 in a cross build (label emulated).
string(REPLACE "|" ";" emulator "${EMULATOR}")
execute_process(
  COMMAND ${emulator} "${EXE}" --benchmark_min_time=0.000001 --benchmark_format=json
  OUTPUT_VARIABLE json ERROR_VARIABLE errors RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${EXE} exited with ${status}: ${errors}")
endif()
string(JSON count ERROR_VARIABLE json_error LENGTH "${json}" benchmarks)
if(json_error OR count EQUAL 0)
  message(FATAL_ERROR "${EXE} printed no benchmark results: ${json_error}\n${errors}")
endif()
set(failed "")
math(EXPR last "${count} - 1")
foreach(i RANGE ${last})
  string(JSON name GET "${json}" benchmarks ${i} name)
  string(JSON error_occurred ERROR_VARIABLE missing GET "${json}" benchmarks ${i} error_occurred)
  if(NOT missing AND error_occurred)
    string(JSON message GET "${json}" benchmarks ${i} error_message)
    string(APPEND failed "  ${name}: ${message}\n")
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "${EXE}: benchmarks whose checks failed:\n${failed}")
endif()
message(STATUS "${EXE}: ${count} benchmarks ran, every check held")
