# Standalone build of the module: the library, its exported CMake package, the C++ tests
# (plain GoogleTest, since Debian installs no opencv_ts), the pybind11 Python module and the
# perf suite. Included from ../CMakeLists.txt when not inside an OpenCV build.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
set(CMAKE_CXX_EXTENSIONS OFF)
set(CMAKE_POSITION_INDEPENDENT_CODE ON)

# Sanitizer builds (test/hardening/): "address" is ASan + UBSan, any report fatal; "thread" is
# TSan. The flags are set in the parent scope too, so that the samples and their tests are
# instrumented like the library and the C++ tests. The Python module is not built then (an
# instrumented extension cannot be loaded by an uninstrumented interpreter), nor the install
# consumer test (a separate, uninstrumented project).
set(RCME_SANITIZE "" CACHE STRING "Sanitizers for the library and the C++ tests: address, thread or empty")
set_property(CACHE RCME_SANITIZE PROPERTY STRINGS "" address thread)
option(RCME_FUZZ "Build the libFuzzer target rcme_fuzz_public_api (clang, with RCME_SANITIZE=address)" OFF)
if(RCME_SANITIZE)
  if(RCME_SANITIZE STREQUAL "address")
    set(_rcme_sanitize_flags "-fsanitize=address,undefined -fno-sanitize-recover=all")
  elseif(RCME_SANITIZE STREQUAL "thread")
    set(_rcme_sanitize_flags "-fsanitize=thread")
  else()
    message(FATAL_ERROR "RCME_SANITIZE must be address, thread or empty, got '${RCME_SANITIZE}'")
  endif()
  # Coverage instrumentation for libFuzzer, without libFuzzer's main (only its target has one).
  # Edge coverage only: the comparison tracing that fuzzer-no-link adds (trace-cmp) took about a
  # third of every execution in Eigen's loops and guides nothing in floating-point input.
  if(RCME_FUZZ)
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang" OR NOT RCME_SANITIZE STREQUAL "address")
      message(FATAL_ERROR "RCME_FUZZ needs clang (CMAKE_CXX_COMPILER=clang++) and RCME_SANITIZE=address")
    endif()
    string(APPEND _rcme_sanitize_flags " -fsanitize=fuzzer-no-link -fno-sanitize-coverage=trace-cmp")
    # Counters only in rcme's own functions (the list says why), for the targets of this
    # directory (not CMake's try_compile checks, which run elsewhere). The path is relative to the
    # build directory, where Ninja runs the compiler, so that ccache's key stays the same across
    # clones; ccache does not read the list, so its hash goes on the command line too.
    get_filename_component(_rcme_allowlist
                           "${CMAKE_CURRENT_LIST_DIR}/../misc/fuzz/coverage_allowlist.txt" ABSOLUTE)
    file(RELATIVE_PATH _rcme_allowlist_rel "${CMAKE_BINARY_DIR}" "${_rcme_allowlist}")
    file(MD5 "${_rcme_allowlist}" _rcme_allowlist_md5)
    add_compile_options("-fsanitize-coverage-allowlist=${_rcme_allowlist_rel}"
                        "-DRCME_COVERAGE_ALLOWLIST_MD5=${_rcme_allowlist_md5}")
  endif()
  string(APPEND _rcme_sanitize_flags " -fno-omit-frame-pointer -g")
  foreach(_var CMAKE_CXX_FLAGS CMAKE_EXE_LINKER_FLAGS CMAKE_SHARED_LINKER_FLAGS)
    set(${_var} "${${_var}} ${_rcme_sanitize_flags}")
    set(${_var} "${${_var}}" PARENT_SCOPE)
  endforeach()
  set(RCME_BUILD_PYTHON OFF)
elseif(RCME_FUZZ)
  message(FATAL_ERROR "RCME_FUZZ needs RCME_SANITIZE=address")
endif()

include("${CMAKE_CURRENT_LIST_DIR}/find_opencv.cmake")
rcme_find_opencv()
message(STATUS "rcme: OpenCV ${OpenCV_VERSION} (${OpenCV_DIR}), with opencv_${RCME_OPENCV_GEOMETRY}")
find_package(Eigen3 3.3 REQUIRED NO_MODULE)

set(RCME_MODULE_DIR "${CMAKE_CURRENT_LIST_DIR}/..")
file(GLOB_RECURSE RCME_SOURCES CONFIGURE_DEPENDS "${RCME_MODULE_DIR}/src/*.cpp")
file(GLOB RCME_PUBLIC_HEADERS CONFIGURE_DEPENDS "${RCME_MODULE_DIR}/include/opencv2/rcme/*.hpp")

# The sources are compiled once: the shared library exports only the public API, and the
# C++ tests link the same objects directly to reach the components in cv::rcme::detail.
add_library(rcme_objects OBJECT ${RCME_SOURCES})
set_target_properties(rcme_objects PROPERTIES
  CXX_VISIBILITY_PRESET hidden
  VISIBILITY_INLINES_HIDDEN ON)
# CVAPI_EXPORTS turns CV_EXPORTS into default visibility, as in OpenCV's own module targets.
target_compile_definitions(rcme_objects PRIVATE CVAPI_EXPORTS)
target_compile_options(rcme_objects PRIVATE -Wall -Wextra)
target_include_directories(rcme_objects
  PUBLIC $<BUILD_INTERFACE:${RCME_MODULE_DIR}/include>
  PRIVATE ${RCME_MODULE_DIR}/src)
target_link_libraries(rcme_objects PUBLIC opencv_core opencv_imgproc
  opencv_${RCME_OPENCV_GEOMETRY} Eigen3::Eigen)

add_library(rcme SHARED $<TARGET_OBJECTS:rcme_objects>)
add_library(rcme::rcme ALIAS rcme)
set_target_properties(rcme PROPERTIES
  OUTPUT_NAME opencv_rcme
  VERSION ${PROJECT_VERSION}
  SOVERSION ${PROJECT_VERSION_MAJOR}
  EXPORT_NAME rcme)
target_include_directories(rcme PUBLIC
  $<BUILD_INTERFACE:${RCME_MODULE_DIR}/include>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_link_libraries(rcme PUBLIC opencv_core opencv_${RCME_OPENCV_GEOMETRY}
  PRIVATE opencv_imgproc)

install(TARGETS rcme EXPORT rcmeTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES "${RCME_MODULE_DIR}/include/opencv2/rcme.hpp"
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/opencv2)
install(FILES ${RCME_PUBLIC_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/opencv2/rcme)
set(RCME_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/rcme)
install(EXPORT rcmeTargets NAMESPACE rcme:: DESTINATION ${RCME_CMAKE_DIR})
configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/rcmeConfig.cmake.in"
  "${CMAKE_BINARY_DIR}/rcmeConfig.cmake" INSTALL_DESTINATION ${RCME_CMAKE_DIR})
write_basic_package_version_file("${CMAKE_BINARY_DIR}/rcmeConfigVersion.cmake"
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES "${CMAKE_BINARY_DIR}/rcmeConfig.cmake" "${CMAKE_BINARY_DIR}/rcmeConfigVersion.cmake"
  DESTINATION ${RCME_CMAKE_DIR})

# The interpreter of the Python module and of the Python-run tests: Debian's by default (the one
# python3-numpy, python3-opencv and python3-pytest belong to); -DPython3_EXECUTABLE=... changes it.
if(NOT Python3_EXECUTABLE)
  set(Python3_EXECUTABLE "/usr/bin/python3" CACHE FILEPATH "Python interpreter of the rcme module")
endif()

if(RCME_BUILD_TESTS)
  # The generated tables (src/generated/, misc/python/standalone/generated_bindings.inc) match
  # the public headers: fails naming misc/generate_tables.py when a header changed without them.
  add_test(NAME rcme_generated_tables_up_to_date
    COMMAND "${Python3_EXECUTABLE}" "${RCME_MODULE_DIR}/misc/generate_tables.py" --check)
  set_tests_properties(rcme_generated_tables_up_to_date PROPERTIES
    ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1")

  find_package(GTest REQUIRED)
  find_package(Threads REQUIRED)
  # The TSan job runs the concurrency tests only (test/hardening/run_sanitizers.sh --tsan), so it
  # compiles only their file and the main.
  option(RCME_TESTS_CONCURRENCY_ONLY "Build only the concurrency tests (the TSan job)" OFF)
  if(RCME_TESTS_CONCURRENCY_ONLY)
    set(RCME_TEST_SOURCES "${RCME_MODULE_DIR}/test/test_concurrency.cpp"
      "${RCME_MODULE_DIR}/test/test_main.cpp")
  else()
    file(GLOB RCME_TEST_SOURCES CONFIGURE_DEPENDS "${RCME_MODULE_DIR}/test/*.cpp")
  endif()
  add_executable(opencv_test_rcme ${RCME_TEST_SOURCES})
  # No absolute path of the checkout on the command line: ccache then serves a fresh clone in
  # another folder from the objects of the previous one (CCACHE_BASEDIR, test/run_test_parts.sh).
  target_compile_definitions(opencv_test_rcme PRIVATE RCME_STANDALONE_TESTS)
  target_include_directories(opencv_test_rcme PRIVATE ${RCME_MODULE_DIR}/test ${RCME_MODULE_DIR}/src)
  target_link_libraries(opencv_test_rcme PRIVATE rcme_objects GTest::gtest Threads::Threads
    opencv_imgcodecs)
  include(GoogleTest)
  gtest_discover_tests(opencv_test_rcme DISCOVERY_TIMEOUT 120)
endif()

if(RCME_FUZZ)
  add_subdirectory("${RCME_MODULE_DIR}/misc/fuzz" "${CMAKE_BINARY_DIR}/fuzz")
endif()

if(RCME_BUILD_PYTHON)
  add_subdirectory("${RCME_MODULE_DIR}/misc/python/standalone" "${CMAKE_BINARY_DIR}/python_module")
endif()

if(RCME_BUILD_PERF)
  add_subdirectory("${RCME_MODULE_DIR}/perf" "${CMAKE_BINARY_DIR}/perf")
endif()
