# Unit and sequence tests of the core (GoogleTest). Each test/core/test_*.cpp is one test program,
# linked with every core library; built by the `tests` target, registered with CTest per test case.
find_package(GTest REQUIRED)
include(GoogleTest)
if(NOT TARGET tests)
  add_custom_target(tests)
endif()
file(GLOB OT_CORE_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/core/test_*.cpp)
if(NOT OT_WITH_IMAGE_IO)  # these read or write image files, or use the evaluation's I/O
  list(FILTER OT_CORE_TESTS EXCLUDE REGEX "/test_(eval_runner|pipeline_scenes|scene|sequence|sequence_list)\\.cpp$")
endif()
foreach(src ${OT_CORE_TESTS})
  get_filename_component(name ${src} NAME_WE)
  add_executable(${name} EXCLUDE_FROM_ALL ${src})
  target_link_libraries(${name} ${OT_LIBS} GTest::gtest GTest::gtest_main pthread)
  target_compile_definitions(${name} PRIVATE
    OT_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    OT_SHARED_DIR="${PROJECT_SOURCE_DIR}/../shared")
  add_dependencies(tests ${name})
  gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60
    PROPERTIES LABELS core)
endforeach()

# The command-line tools from the outside (exit codes, messages): test/tools/TOOL_cli.sh runs
# against the built TOOL, for each tool that has one and is built here.
file(GLOB OT_TOOL_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/tools/*_cli.sh)
foreach(script ${OT_TOOL_TESTS})
  get_filename_component(name ${script} NAME_WE)
  string(REGEX REPLACE "_cli$" "" tool ${name})
  if(TARGET ${tool})
    add_test(NAME ${name} COMMAND bash ${script} $<TARGET_FILE:${tool}>)
    add_dependencies(tests ${tool})  # builds that make only `tests` (sanitizers) run it too
    set_tests_properties(${name} PROPERTIES LABELS tools TIMEOUT 60)
  endif()
endforeach()
# track_sequence_cli.sh renders its input with generate_scene, taken from beside track_sequence.
if(TARGET track_sequence AND TARGET generate_scene)
  add_dependencies(tests generate_scene)
endif()
