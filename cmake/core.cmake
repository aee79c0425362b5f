# The ROS-free core: OpenCV (core, imgproc, video, calib3d), Eigen, yaml-cpp (parameter files)
# and the standard library. Every .cpp in src/core belongs to it.
# yaml-cpp is found by hand rather than through its CMake config so that cross-builds work:
# libyaml-cpp-dev cannot be installed for two architectures at once, so an arm64 build links the
# runtime package (libyaml-cpp0.7:arm64) with the architecture-independent headers of the host's.
find_path(OT_YAML_CPP_INCLUDE_DIR yaml-cpp/yaml.h REQUIRED)
find_library(OT_YAML_CPP_LIB NAMES yaml-cpp libyaml-cpp.so.0.7 REQUIRED)
file(GLOB OT_CORE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/core/*.cpp)
add_library(obstacle_tracker_core ${OT_CORE_SOURCES})
target_include_directories(obstacle_tracker_core PUBLIC
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
target_include_directories(obstacle_tracker_core SYSTEM PUBLIC ${OpenCV_INCLUDE_DIRS} ${EIGEN3_INCLUDE_DIR})
target_include_directories(obstacle_tracker_core SYSTEM PRIVATE ${OT_YAML_CPP_INCLUDE_DIR})
# Only the modules the core includes; the tools and the nodelet link what else they use.
set(OT_CORE_OPENCV_LIBS opencv_core opencv_imgproc opencv_video opencv_calib3d)
if(OT_OPENCV_MINIMAL)
  set(OT_CORE_OPENCV_LIBS ${OpenCV_LIBS})
endif()
target_link_libraries(obstacle_tracker_core PUBLIC ${OT_CORE_OPENCV_LIBS} PRIVATE ${OT_YAML_CPP_LIB})
set_target_properties(obstacle_tracker_core PROPERTIES POSITION_INDEPENDENT_CODE ON)

# Synthetic flight scenes (tests, demo, benchmarks): src/scene. scene_io writes image files.
file(GLOB OT_SCENE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/scene/*.cpp)
if(NOT OT_WITH_IMAGE_IO)
  list(FILTER OT_SCENE_SOURCES EXCLUDE REGEX "scene_io\\.cpp$")
endif()
if(OT_SCENE_SOURCES)
  add_library(obstacle_tracker_scene ${OT_SCENE_SOURCES})
  target_link_libraries(obstacle_tracker_scene PUBLIC obstacle_tracker_core ${OpenCV_LIBS})
  set_target_properties(obstacle_tracker_scene PROPERTIES POSITION_INDEPENDENT_CODE ON)
  list(APPEND OT_LIBS obstacle_tracker_scene)
endif()

# Evaluation: ground-truth parsing, OTB / long-term metrics, OpenCV reference trackers: src/eval.
# Without image I/O (cross-builds) only the metrics.
file(GLOB OT_EVAL_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/eval/*.cpp)
if(NOT OT_WITH_IMAGE_IO)
  list(FILTER OT_EVAL_SOURCES INCLUDE REGEX "metrics\\.cpp$")
endif()
if(OT_EVAL_SOURCES)
  add_library(obstacle_tracker_eval ${OT_EVAL_SOURCES})
  target_link_libraries(obstacle_tracker_eval PUBLIC obstacle_tracker_core ${OpenCV_LIBS})
  set_target_properties(obstacle_tracker_eval PROPERTIES POSITION_INDEPENDENT_CODE ON)
  list(APPEND OT_LIBS obstacle_tracker_eval)
endif()
list(APPEND OT_LIBS obstacle_tracker_core)

# Command-line tools: each src/tools/NAME.cpp is the main of the executable NAME, linked with
# every library above; a tool too large for one file keeps its other parts in src/tools/NAME/
# (included as "NAME/part.h"). Under catkin they land in devel/lib/obstacle_tracker (rosrun
# finds them). They read their command line with CLI11 (header-only, so found by hand like
# yaml-cpp: the host's headers serve a cross-build too); src/tools/command_line.h holds the
# conventions they share (help, usage errors, exit codes).
find_path(OT_CLI11_INCLUDE_DIR CLI/CLI.hpp REQUIRED)
file(GLOB OT_TOOL_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/tools/*.cpp)
if(NOT OT_WITH_IMAGE_IO)  # the tools that read no image file
  list(FILTER OT_TOOL_SOURCES INCLUDE REGEX "/(print_params|scene_boxes)\\.cpp$")
endif()
foreach(src ${OT_TOOL_SOURCES})
  get_filename_component(name ${src} NAME_WE)
  file(GLOB parts CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/tools/${name}/*.cpp)
  add_executable(${name} ${src} ${parts})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/src/tools)
  target_include_directories(${name} SYSTEM PRIVATE ${OT_CLI11_INCLUDE_DIR})
  target_link_libraries(${name} ${OT_LIBS})
  if(OT_TOOL_OUTPUT_DIR)
    set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${OT_TOOL_OUTPUT_DIR})
  endif()
  list(APPEND OT_TOOLS ${name})
endforeach()
