# Google Benchmark programs, kept apart from the tests: `cmake --build _build --target bench_core`.
find_package(benchmark QUIET)
file(GLOB OT_BENCH_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/bench/bench_*.cpp)
if(benchmark_FOUND AND OT_BENCH_SOURCES)
  add_executable(bench_core EXCLUDE_FROM_ALL ${OT_BENCH_SOURCES})
  target_link_libraries(bench_core ${OT_LIBS} benchmark::benchmark benchmark::benchmark_main)
endif()
