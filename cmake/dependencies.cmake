# Every dependency comes from Debian 12's packages (see README.md).
find_package(embree 3 REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenImageIO 2.4 REQUIRED)
# OpenImageIO's exported target names /usr/include/opencv4, which exists only with
# OpenCV's dev package installed; drop it so the generate step does not fail. OpenCV is now a
# dependency of its own (below), so the folder is there; the filter stays so that OpenCV's
# headers reach only the targets that link OpenCV (relight_lib, privately).
get_target_property(_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
if(_oiio_inc)
  list(FILTER _oiio_inc EXCLUDE REGEX "opencv4")
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_inc}")
endif()
# The rectified fill of removed objects' surfaces: cv::inpaint as the baseline
# (relight/dynamic/rectified_fill.h). Debian's libopencv-dev 4.6. calib3d for the tests only
# (cv::findHomography checks the plane homographies of relight/dynamic/plane_homography.h).
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc photo calib3d)
find_package(glm REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 2 REQUIRED)
find_package(TBB REQUIRED)
# PLY and glTF geometry (relight/io/mesh_reader.h). Debian's config also needs draco's, which
# libassimp-dev pulls in.
find_package(assimp 5 CONFIG QUIET)
if(NOT assimp_FOUND)
  message(FATAL_ERROR "Assimp (the PLY and glTF reader) not found: install Debian's "
                      "libassimp-dev (bash scripts/install-deps.sh installs every dependency)")
endif()
if(RELIGHT_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
