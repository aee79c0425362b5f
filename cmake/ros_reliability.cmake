# Reliability rostests, catkin mode only; included at the end of cmake/ros.cmake.
#   test/ros/reliability/bad_input.test  every kind of bad image, parameter, camera_info and tf
#   test/ros/reliability/load.test       1280x720 at 200 Hz for 60 s: which frames are answered,
#                                        memory, drops
# Each NAME.test is run by the test node reliability_NAME (test/ros/reliability/NAME.cpp and its
# parts, GoogleTest inside rostest). The load test runs alone (RUN_SERIAL): it saturates both cores and
# would only lengthen the tests beside it.
if(NOT CATKIN_ENABLE_TESTING)
  return()
endif()

set(OT_RELIABILITY_DIR test/ros/reliability)
set(OT_LOAD_SECONDS 60 CACHE STRING "Duration of the reliability load rostest (s)")
# bad_input.cpp's BadInput suite runs first (GoogleTest runs suites in the order they register);
# BadGeometry uses its own tracker and waits for it, so the order is not relied on.
set(OT_RELIABILITY_bad_input_EXTRA ${OT_RELIABILITY_DIR}/bad_geometry.cpp ${OT_RELIABILITY_DIR}/bad_input_harness.cpp)
foreach(name bad_input load)
  catkin_add_executable_with_gtest(reliability_${name} ${OT_RELIABILITY_DIR}/${name}.cpp
    ${OT_RELIABILITY_${name}_EXTRA} EXCLUDE_FROM_ALL)
  target_link_libraries(reliability_${name} obstacle_tracker_nodelet ${OT_LIBS} ${catkin_LIBRARIES})
  set_target_properties(reliability_${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${OT_ROS_BIN_DIR})
  add_dependencies(reliability_${name} ${PROJECT_NAME}_generate_messages_cpp)
  add_dependencies(tests reliability_${name})
endforeach()
add_rostest(${OT_RELIABILITY_DIR}/bad_input.test
  DEPENDENCIES obstacle_tracker_nodelet reliability_bad_input)
add_rostest(${OT_RELIABILITY_DIR}/load.test ARGS duration:=${OT_LOAD_SECONDS}
  DEPENDENCIES obstacle_tracker_nodelet reliability_load)
# catkin names the CTest test after the file name and the arguments
# (_ctest_<package>_rostest_load__duration_60.test); find it among the directory's tests.
get_property(OT_DIR_TESTS DIRECTORY ${PROJECT_SOURCE_DIR} PROPERTY TESTS)
foreach(t ${OT_DIR_TESTS})
  if(t MATCHES "_rostest_load__duration_")
    set_tests_properties(${t} PROPERTIES RUN_SERIAL TRUE)
  endif()
endforeach()
