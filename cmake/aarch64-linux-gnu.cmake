# Cross-build for ARM64 (aarch64) companion computers with Debian's multiarch packages:
#   apt-get install g++-aarch64-linux-gnu qemu-user libopencv-core-dev:arm64 \
#     libopencv-imgproc-dev:arm64 libopencv-video406:arm64 libopencv-calib3d406:arm64 libgtest-dev:arm64 \
#     libyaml-cpp0.7:arm64
#   cmake -S . -B _build/arm64 -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake -DOT_CORE_ONLY=ON
# The test programs run under qemu-user (CMAKE_CROSSCOMPILING_EMULATOR), so ctest works as usual.
# Debian's arm64 OpenCV packages ship no CMake config and imgcodecs/videoio:arm64 cannot be
# installed beside the amd64 ones (their GDAL dependencies conflict): the build finds the modules
# the core uses itself (cmake/opencv_minimal.cmake) and leaves out what needs image files.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64)
# Multiarch: the arm64 libraries live in /usr/lib/aarch64-linux-gnu of this very system.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(OT_OPENCV_MINIMAL ON CACHE BOOL "find only the OpenCV modules the core uses (no CMake config for this target)")
