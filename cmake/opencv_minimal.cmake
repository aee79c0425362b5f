# OpenCV core + imgproc without OpenCV's CMake config (Debian's arm64 packages have none): the
# headers (common and per-architecture cvconfig.h) and the two libraries, as OpenCV_INCLUDE_DIRS
# and OpenCV_LIBS like find_package(OpenCV) sets them. Used by cross-builds (OT_OPENCV_MINIMAL).
find_path(OT_OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
find_path(OT_OPENCV_CONFIG_DIR opencv2/cvconfig.h
  PATHS /usr/include/${CMAKE_LIBRARY_ARCHITECTURE}/opencv4 PATH_SUFFIXES opencv4 REQUIRED)
find_library(OT_OPENCV_CORE_LIB opencv_core REQUIRED)
find_library(OT_OPENCV_IMGPROC_LIB opencv_imgproc REQUIRED)
set(OpenCV_INCLUDE_DIRS ${OT_OPENCV_CONFIG_DIR} ${OT_OPENCV_INCLUDE_DIR})
set(OpenCV_LIBS ${OT_OPENCV_IMGPROC_LIB} ${OT_OPENCV_CORE_LIB})
message(STATUS "OpenCV core + imgproc only: ${OpenCV_LIBS}")
