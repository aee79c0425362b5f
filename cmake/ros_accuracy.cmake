# Accuracy rostests driven by rosbags, catkin mode only; included at the end of cmake/ros.cmake.
# At build time (`tests` target):
#   - generate_scene renders a flight scene and scripts/sequence_to_bag.py turns it into
#     accuracy/scene.bag (images + camera_info + /ground_truth);
#   - when ../shared/sequences/${OT_ACCURACY_SEQUENCE} exists, the same converter makes
#     accuracy/real.bag from it (the bag stays in the build folder; nothing is copied into the
#     package).
# test/ros/accuracy/accuracy_scene.test and accuracy_real.test send them through the real nodelet
# in a manager; accuracy_node asserts which frames are answered (with their header, once, in
# order, dropped only while the tracker is busy) and, sent lock-step, OTB precision/success bars
# (why not in real time: accuracy_node.cpp). Without the shared folder the real test is
# registered anyway and reports that it is skipped and why.
if(NOT CATKIN_ENABLE_TESTING)
  return()
endif()

set(OT_ACCURACY_DIR ${CMAKE_CURRENT_BINARY_DIR}/accuracy)
# A scene the auto-initialised core handles (evaluate --init auto scores it above the bars below),
# so the ROS path must keep the core's accuracy.
set(OT_ACCURACY_SCENE "bird" CACHE STRING "generate_scene scenario of the accuracy rostest")
set(OT_ACCURACY_SCENE_SEED 3 CACHE STRING "generate_scene seed of the accuracy rostest")
set(OT_ACCURACY_SCENE_SIZE 480x360 CACHE STRING "frame size of the accuracy rostest scene")
# antiuav_ir_09: a clip whose auto-initialised score is stable under small parameter changes, so
# that the bar tests the ROS path rather than the auto-initialiser's luck.
set(OT_ACCURACY_SEQUENCE "antiuav_ir_09" CACHE STRING "shared sequence replayed by the real accuracy rostest")
set(OT_ACCURACY_SEQUENCE_FRAMES 300 CACHE STRING "frames of the shared sequence put in the bag")
# Bars (OTB precision at 20 px / success AUC of the nodelet's best obstacle, auto-initialised).
set(OT_ACCURACY_SCENE_BARS min_precision20:=0.80 min_auc:=0.40)
set(OT_ACCURACY_SCENE_720_BARS min_precision20:=0.80 min_auc:=0.40)
set(OT_ACCURACY_REAL_BARS min_precision20:=0.7 min_auc:=0.35)

set(OT_ACCURACY_PYTHONPATH ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_PYTHON_DESTINATION})
set(OT_TO_BAG ${PROJECT_SOURCE_DIR}/scripts/sequence_to_bag.py)
# The bags hold ObstacleArray ground truth: a changed message definition must remake them. The
# converter reads the ground-truth file with the score_boxes tool (the package's one reader).
set(OT_TO_BAG_DEPS ${OT_TO_BAG} ${PROJECT_SOURCE_DIR}/scripts/score_boxes_tool.py score_boxes
  ${PROJECT_SOURCE_DIR}/msg/Obstacle.msg ${PROJECT_SOURCE_DIR}/msg/ObstacleArray.msg
  ${PROJECT_NAME}_generate_messages_py)
set(OT_TO_BAG_ARGS --frame-id camera_optical --score-boxes $<TARGET_FILE:score_boxes>)

# One bag per size: the accuracy size, sent lock-step (the bars); 1280x720, sent lock-step (the
# bars) and also at its 30 Hz like a camera (frames the tracker cannot take are dropped, and must
# be dropped only then). Each config file is rewritten only when the choice changes, so that a
# new choice remakes the bag.
set(OT_ACCURACY_BAGS)
foreach(variant scene scene_720)
  if(variant STREQUAL "scene")
    set(size ${OT_ACCURACY_SCENE_SIZE})
  else()
    set(size 1280x720)
  endif()
  file(CONFIGURE OUTPUT ${OT_ACCURACY_DIR}/${variant}.cfg
    CONTENT "${OT_ACCURACY_SCENE} ${OT_ACCURACY_SCENE_SEED} ${size}\n")
  add_custom_command(OUTPUT ${OT_ACCURACY_DIR}/${variant}.bag
    COMMAND ${CMAKE_COMMAND} -E remove_directory ${OT_ACCURACY_DIR}/${variant}
    COMMAND $<TARGET_FILE:generate_scene> --scenario ${OT_ACCURACY_SCENE} --seed ${OT_ACCURACY_SCENE_SEED}
            --frames 150 --size ${size} --quiet --out ${OT_ACCURACY_DIR}/${variant}
    COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${OT_ACCURACY_PYTHONPATH}
            /usr/bin/python3 ${OT_TO_BAG} ${OT_ACCURACY_DIR}/${variant} ${OT_ACCURACY_DIR}/${variant}.bag
            ${OT_TO_BAG_ARGS} --quiet
    COMMAND ${CMAKE_COMMAND} -E remove_directory ${OT_ACCURACY_DIR}/${variant}
    DEPENDS generate_scene ${OT_TO_BAG_DEPS} ${OT_ACCURACY_DIR}/${variant}.cfg
    COMMENT "accuracy rostest: scene ${OT_ACCURACY_SCENE} ${size} -> accuracy/${variant}.bag"
    VERBATIM)
  list(APPEND OT_ACCURACY_BAGS ${OT_ACCURACY_DIR}/${variant}.bag)
endforeach()

set(OT_ACCURACY_SHARED ${PROJECT_SOURCE_DIR}/../shared/sequences/${OT_ACCURACY_SEQUENCE})
if(EXISTS ${OT_ACCURACY_SHARED}/groundtruth_rect.txt)
  add_custom_command(OUTPUT ${OT_ACCURACY_DIR}/real.bag
    COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${OT_ACCURACY_PYTHONPATH}
            /usr/bin/python3 ${OT_TO_BAG} ${OT_ACCURACY_SHARED} ${OT_ACCURACY_DIR}/real.bag
            ${OT_TO_BAG_ARGS} --encoding mono8 --max-frames ${OT_ACCURACY_SEQUENCE_FRAMES} --quiet
    DEPENDS ${OT_TO_BAG_DEPS} ${OT_ACCURACY_SHARED}/groundtruth_rect.txt
    COMMENT "accuracy rostest: ${OT_ACCURACY_SEQUENCE} -> accuracy/real.bag"
    VERBATIM)
  list(APPEND OT_ACCURACY_BAGS ${OT_ACCURACY_DIR}/real.bag)
  set(OT_ACCURACY_REAL_ARGS name:=${OT_ACCURACY_SEQUENCE} bag:=${OT_ACCURACY_DIR}/real.bag ${OT_ACCURACY_REAL_BARS})
else()
  set(OT_ACCURACY_REAL_ARGS name:=${OT_ACCURACY_SEQUENCE} missing:=${OT_ACCURACY_SHARED})
endif()
add_custom_target(accuracy_bags DEPENDS ${OT_ACCURACY_BAGS})
add_dependencies(tests accuracy_bags)

catkin_add_executable_with_gtest(accuracy_node test/ros/accuracy/accuracy_node.cpp EXCLUDE_FROM_ALL)
target_link_libraries(accuracy_node obstacle_tracker_nodelet ${OT_LIBS} ${catkin_LIBRARIES})
set_target_properties(accuracy_node PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${OT_ROS_BIN_DIR})
add_dependencies(accuracy_node ${PROJECT_NAME}_generate_messages_cpp)
add_dependencies(tests accuracy_node)

# name:= first: rostest names a test's result file after its arguments up to the first '.', and a
# build path with a dot in it (a mktemp folder) would give the scene tests the same file, which
# the one finishing last overwrites while another's result is being read (ctest -j).
add_rostest(test/ros/accuracy/accuracy_scene.test
  ARGS name:=scene bag:=${OT_ACCURACY_DIR}/scene.bag ${OT_ACCURACY_SCENE_BARS}
  DEPENDENCIES obstacle_tracker_nodelet accuracy_node accuracy_bags)
add_rostest(test/ros/accuracy/accuracy_scene.test
  ARGS name:=scene_720 bag:=${OT_ACCURACY_DIR}/scene_720.bag ${OT_ACCURACY_SCENE_720_BARS}
  DEPENDENCIES obstacle_tracker_nodelet accuracy_node accuracy_bags)
add_rostest(test/ros/accuracy/accuracy_scene.test
  ARGS name:=scene_720_realtime bag:=${OT_ACCURACY_DIR}/scene_720.bag pace:=realtime ${OT_ACCURACY_SCENE_720_BARS}
  DEPENDENCIES obstacle_tracker_nodelet accuracy_node accuracy_bags)
add_rostest(test/ros/accuracy/accuracy_real.test ARGS ${OT_ACCURACY_REAL_ARGS}
  DEPENDENCIES obstacle_tracker_nodelet accuracy_node accuracy_bags)
