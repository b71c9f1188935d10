# The installed OpenCV of the standalone build (4.6 or later, 5.x included) and the modules rcme
# and its samples link. Up to 4.x findFundamentalMat, findEssentialMat and recoverPose are in
# calib3d and the feature detectors in features2d; OpenCV 5 split calib3d (those functions are in
# geometry from 5.1 on, in 3d in 5.0) and renamed features2d to features. The module's
# CMakeLists.txt makes the same choice inside an OpenCV build, and
# include/opencv2/rcme/opencv_geometry.hpp includes the matching header.
#
# rcme_find_opencv([extra components]) sets RCME_OPENCV_GEOMETRY and RCME_OPENCV_FEATURES (module
# names without opencv_) and finds OpenCV with core, imgproc, that module and the extra
# components; in the extras, "features" stands for RCME_OPENCV_FEATURES.
macro(rcme_find_opencv)
  # Without a version: OpenCV's package accepts only a request of its own major version.
  find_package(OpenCV REQUIRED COMPONENTS core)
  if(OpenCV_VERSION VERSION_LESS 4.6)
    message(FATAL_ERROR "rcme needs OpenCV 4.6 or later, found ${OpenCV_VERSION} in ${OpenCV_DIR}")
  endif()
  set(RCME_OPENCV_GEOMETRY "")
  foreach(_rcme_m geometry 3d calib3d)
    if(NOT RCME_OPENCV_GEOMETRY AND "opencv_${_rcme_m}" IN_LIST OpenCV_LIB_COMPONENTS)
      set(RCME_OPENCV_GEOMETRY ${_rcme_m})
    endif()
  endforeach()
  if(NOT RCME_OPENCV_GEOMETRY)
    message(FATAL_ERROR "OpenCV ${OpenCV_VERSION} in ${OpenCV_DIR} has none of the modules "
                        "geometry, 3d, calib3d (findFundamentalMat & co.)")
  endif()
  if("opencv_features" IN_LIST OpenCV_LIB_COMPONENTS)
    set(RCME_OPENCV_FEATURES features)
  else()
    set(RCME_OPENCV_FEATURES features2d)
  endif()
  set(_rcme_components core imgproc ${RCME_OPENCV_GEOMETRY})
  foreach(_rcme_m ${ARGN})
    if(_rcme_m STREQUAL "features")
      list(APPEND _rcme_components ${RCME_OPENCV_FEATURES})
    else()
      list(APPEND _rcme_components ${_rcme_m})
    endif()
  endforeach()
  find_package(OpenCV REQUIRED COMPONENTS ${_rcme_components})
endmacro()
