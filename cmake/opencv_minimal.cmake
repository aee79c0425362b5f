# The OpenCV modules the core uses (core, imgproc, video, calib3d) without OpenCV's CMake config
# (Debian's arm64 packages have none): the headers (common and per-architecture cvconfig.h) and the
# libraries, as OpenCV_INCLUDE_DIRS and OpenCV_LIBS like find_package(OpenCV) sets them. Used by
# cross-builds (OT_OPENCV_MINIMAL). video and calib3d come as runtime packages only
# (libopencv-video406:arm64, libopencv-calib3d406:arm64: their -dev packages cannot be installed
# beside the amd64 OpenCV), so their versioned library names are searched too; their headers are
# the architecture-independent ones of the host's OpenCV.
find_path(OT_OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
find_path(OT_OPENCV_CONFIG_DIR opencv2/cvconfig.h
  PATHS /usr/include/${CMAKE_LIBRARY_ARCHITECTURE}/opencv4 PATH_SUFFIXES opencv4 REQUIRED)
find_library(OT_OPENCV_CORE_LIB opencv_core REQUIRED)
find_library(OT_OPENCV_IMGPROC_LIB opencv_imgproc REQUIRED)
find_library(OT_OPENCV_VIDEO_LIB NAMES opencv_video libopencv_video.so.406 REQUIRED)
find_library(OT_OPENCV_CALIB3D_LIB NAMES opencv_calib3d libopencv_calib3d.so.406 REQUIRED)
set(OpenCV_INCLUDE_DIRS ${OT_OPENCV_CONFIG_DIR} ${OT_OPENCV_INCLUDE_DIR})
set(OpenCV_LIBS ${OT_OPENCV_CALIB3D_LIB} ${OT_OPENCV_VIDEO_LIB} ${OT_OPENCV_IMGPROC_LIB} ${OT_OPENCV_CORE_LIB})
message(STATUS "OpenCV for the core only: ${OpenCV_LIBS}")
