# ROS side of the package (catkin mode only; included from CMakeLists.txt after core.cmake):
# the nodelet library, the standalone node and other executables of nodes/, the ROS unit tests and
# the rostests. Outputs go to devel/lib/obstacle_tracker (rosrun / roslaunch find them there).

set(OT_ROS_BIN_DIR ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
set(OT_GENERATED_INCLUDE_DIR ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})

# config/ObstacleTracker.cfg reads its parameter list from params.h: regenerate the config header
# (and the Python module) when params.h changes, not only when the .cfg does.
add_custom_command(OUTPUT ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_INCLUDE_DESTINATION}/ObstacleTrackerConfig.h
  APPEND DEPENDS ${PROJECT_SOURCE_DIR}/include/obstacle_tracker/core/params.h)

# The nodelet and the conversions between core types and messages: src/ros/*.cpp.
file(GLOB OT_ROS_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/ros/*.cpp)
add_library(obstacle_tracker_nodelet ${OT_ROS_SOURCES})
target_include_directories(obstacle_tracker_nodelet PUBLIC
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<BUILD_INTERFACE:${OT_GENERATED_INCLUDE_DIR}>)
target_include_directories(obstacle_tracker_nodelet SYSTEM PUBLIC ${catkin_INCLUDE_DIRS})
target_link_libraries(obstacle_tracker_nodelet PUBLIC obstacle_tracker_core ${catkin_LIBRARIES})
# Generated message headers and ObstacleTrackerConfig.h must exist before the sources compile.
add_dependencies(obstacle_tracker_nodelet ${PROJECT_NAME}_generate_messages_cpp ${PROJECT_NAME}_gencfg)
set_target_properties(obstacle_tracker_nodelet PROPERTIES
  LIBRARY_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_LIB_DESTINATION})

# Executables: each nodes/NAME.cpp is the main of NAME (obstacle_tracker_node loads the nodelet
# in-process), linked with the nodelet and every core library.
file(GLOB OT_NODE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/nodes/*.cpp)
set(OT_NODES)
foreach(src ${OT_NODE_SOURCES})
  get_filename_component(name ${src} NAME_WE)
  add_executable(${name} ${src})
  target_link_libraries(${name} obstacle_tracker_nodelet ${OT_LIBS})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${OT_ROS_BIN_DIR})
  list(APPEND OT_NODES ${name})
endforeach()

install(TARGETS obstacle_tracker_nodelet ${OT_NODES}
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
# (nodelet_plugins.xml, launch/ and config/ are installed by CMakeLists.txt; the .msg files by catkin.)

if(CATKIN_ENABLE_TESTING)
  # catkin creates `tests`; cmake/tests.cmake (included after this file) does when it did not.
  if(NOT TARGET tests)
    add_custom_target(tests)
  endif()
  find_package(rostest REQUIRED)
  find_package(GTest REQUIRED)
  include(GoogleTest)

  # ROS-side unit tests without a master (conversions, geometry, parameter mapping):
  # test/ros/test_*.cpp, one GoogleTest program each, registered per test case.
  file(GLOB OT_ROS_UNIT_TESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/ros/test_*.cpp)
  foreach(src ${OT_ROS_UNIT_TESTS})
    get_filename_component(name ${src} NAME_WE)
    add_executable(${name} EXCLUDE_FROM_ALL ${src})
    target_link_libraries(${name} obstacle_tracker_nodelet ${OT_LIBS} GTest::gtest GTest::gtest_main pthread)
    set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${OT_ROS_BIN_DIR})
    add_dependencies(tests ${name})
    gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60 PROPERTIES LABELS ros)
  endforeach()

  # rostest nodes: test/ros/rostest_*.cpp (GoogleTest inside a rostest launch) and
  # test/ros/tool_*.cpp (helpers the .test files start: image publishers, bag writers).
  file(GLOB OT_ROSTEST_NODES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/ros/rostest_*.cpp)
  foreach(src ${OT_ROSTEST_NODES})
    get_filename_component(name ${src} NAME_WE)
    catkin_add_executable_with_gtest(${name} ${src} EXCLUDE_FROM_ALL)
    target_link_libraries(${name} obstacle_tracker_nodelet ${OT_LIBS})
    set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${OT_ROS_BIN_DIR})
    add_dependencies(tests ${name})
    list(APPEND OT_ROSTEST_DEPS ${name})
  endforeach()
  file(GLOB OT_ROSTEST_TOOLS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/ros/tool_*.cpp)
  foreach(src ${OT_ROSTEST_TOOLS})
    get_filename_component(name ${src} NAME_WE)
    add_executable(${name} EXCLUDE_FROM_ALL ${src})
    target_link_libraries(${name} obstacle_tracker_nodelet ${OT_LIBS})
    set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${OT_ROS_BIN_DIR})
    add_dependencies(tests ${name})
    list(APPEND OT_ROSTEST_DEPS ${name})
  endforeach()

  # Each test/ros/*.test is one rostest (its own master; real nodelet manager or node).
  file(GLOB OT_ROSTESTS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/ros/*.test)
  foreach(launch ${OT_ROSTESTS})
    file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR} ${launch})
    add_rostest(${rel} DEPENDENCIES obstacle_tracker_nodelet ${OT_NODES} ${OT_ROSTEST_DEPS})
  endforeach()

  # rviz shows the overlay as its main view: rviz under Xvfb with config/obstacle_tracker.rviz, a
  # screenshot, the box colour, the overlay's share of the screen and the bearing arrow found in it
  # (skipped with a message where rviz / Xvfb / ImageMagick are missing).
  add_test(NAME rviz_overlay_screenshot
    COMMAND bash ${PROJECT_SOURCE_DIR}/test/ros/rviz_screenshot.sh ${CATKIN_DEVEL_PREFIX}
            ${CMAKE_BINARY_DIR}/test_results/rviz)
  set_tests_properties(rviz_overlay_screenshot PROPERTIES LABELS ros TIMEOUT 300)
endif()
include(cmake/ros_accuracy.cmake OPTIONAL)
include(cmake/ros_reliability.cmake OPTIONAL)
