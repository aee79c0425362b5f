# libFuzzer targets (fuzz/fuzz_*.cpp), only with -DOT_FUZZ=ON and clang:
#   CC=clang CXX=clang++ cmake -S . -B _build/fuzz -DOT_CORE_ONLY=ON -DOT_FUZZ=ON
#   cmake --build _build/fuzz --target fuzzers
# The core libraries are then compiled with coverage instrumentation for the fuzzer
# (-fsanitize=fuzzer-no-link) plus ASan and UBSan; each fuzz_NAME links libFuzzer's main.
# fuzz_make_seeds writes the seed corpora (scripts/extra_tests.d/20-fuzz.sh runs it all).
if(NOT OT_FUZZ)
  return()
endif()
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "OT_FUZZ needs clang (libFuzzer): configure with CC=clang CXX=clang++")
endif()

set(OT_FUZZ_SANITIZERS -fsanitize=address,undefined -fno-sanitize-recover=undefined
    -fno-omit-frame-pointer -g)
foreach(lib ${OT_LIBS})
  target_compile_options(${lib} PRIVATE -fsanitize=fuzzer-no-link ${OT_FUZZ_SANITIZERS})
  target_link_options(${lib} INTERFACE -fsanitize=address,undefined)
endforeach()

if(NOT TARGET fuzzers)
  add_custom_target(fuzzers)
endif()

file(GLOB OT_FUZZ_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/fuzz/fuzz_*.cpp)
# fuzz_pipeline needs the Pipeline implementation (src/core/pipeline*.cpp).
file(GLOB OT_FUZZ_PIPELINE_IMPL CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/core/pipeline*.cpp)
foreach(src ${OT_FUZZ_SOURCES})
  get_filename_component(name ${src} NAME_WE)
  if(name STREQUAL "fuzz_pipeline" AND NOT OT_FUZZ_PIPELINE_IMPL)
    message(STATUS "fuzz_pipeline skipped: no src/core/pipeline*.cpp yet")
    continue()
  endif()
  add_executable(${name} EXCLUDE_FROM_ALL ${src})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/fuzz)
  target_compile_options(${name} PRIVATE -fsanitize=fuzzer ${OT_FUZZ_SANITIZERS})
  target_link_options(${name} PRIVATE -fsanitize=fuzzer,address,undefined)
  target_link_libraries(${name} obstacle_tracker_core)
  add_dependencies(fuzzers ${name})
endforeach()

# Seed corpora are generated, not stored: fuzz_make_seeds OUTDIR writes OUTDIR/<target>/seed_*.
add_executable(fuzz_make_seeds EXCLUDE_FROM_ALL ${PROJECT_SOURCE_DIR}/fuzz/make_seeds.cpp)
target_include_directories(fuzz_make_seeds PRIVATE ${PROJECT_SOURCE_DIR}/fuzz)
target_compile_options(fuzz_make_seeds PRIVATE ${OT_FUZZ_SANITIZERS})
target_link_libraries(fuzz_make_seeds obstacle_tracker_core)
add_dependencies(fuzzers fuzz_make_seeds)
