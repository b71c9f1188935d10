# Checks used by the CTest tests of samples/CMakeLists.txt (run with cmake -P).
#   -DMODE=png -DFILE=<png>: FILE exists and starts with the PNG signature.
#   -DMODE=jpeg -DFILE=<jpg>: FILE exists and starts with the JPEG signature.
#   -DMODE=missing -DDEMO=<demo> -DFILE=<path>: the demo given the missing image FILE exits with 2
#   and names FILE in its message.
#   -DMODE=missing_data -DDEMO=<mono_vo> -DFILE=<folder>: mono_vo given the missing data folder
#   FILE exits with 2 and names FILE in its message.
#   -DMODE=run -DDEMO=<sample> -DARGS=<a;b;...> -DEXPECT=<regex>: the sample run with ARGS exits
#   with 0 and its output matches every regex of the list EXPECT.
#   -DMODE=two_builds -DDEMO=<cv build> -DDEMO_RCME=<cv::rcme build> -DARGS=<a;b;...>: both builds
#   of opencv_style_vo run to the end (exit 0) and their summary lines are printed side by side.
if(MODE STREQUAL "png" OR MODE STREQUAL "jpeg")
  if(NOT EXISTS "${FILE}")
    message(FATAL_ERROR "the demo did not write ${FILE}")
  endif()
  if(MODE STREQUAL "png")
    file(READ "${FILE}" signature LIMIT 8 HEX)
    set(expected "89504e470d0a1a0a")
  else()
    file(READ "${FILE}" signature LIMIT 3 HEX)
    set(expected "ffd8ff")
  endif()
  if(NOT signature STREQUAL expected)
    message(FATAL_ERROR "${FILE} is not a ${MODE} file (signature ${signature})")
  endif()
  message(STATUS "${FILE} is a ${MODE} file")
elseif(MODE STREQUAL "missing" OR MODE STREQUAL "missing_data")
  file(REMOVE "${FILE}")
  if(MODE STREQUAL "missing")
    execute_process(COMMAND "${DEMO}" "${FILE}" "${FILE}"
      RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  else()
    execute_process(COMMAND "${DEMO}" --data "${FILE}" --out "${FILE}.png"
      RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  endif()
  if(NOT result EQUAL 2)
    message(FATAL_ERROR "expected exit code 2 for a missing input, got '${result}'\n${out}${err}")
  endif()
  string(FIND "${out}${err}" "${FILE}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "the message does not name the missing file ${FILE}:\n${out}${err}")
  endif()
  message(STATUS "missing input reported: ${err}")
elseif(MODE STREQUAL "run")
  execute_process(COMMAND "${DEMO}" ${ARGS}
    RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "expected exit code 0, got '${result}'\n${out}${err}")
  endif()
  foreach(expected IN LISTS EXPECT)
    if(NOT "${out}" MATCHES "${expected}")
      message(FATAL_ERROR "the output does not match '${expected}':\n${out}${err}")
    endif()
  endforeach()
  message(STATUS "${out}")
elseif(MODE STREQUAL "two_builds")
  set(summary "")
  foreach(build IN ITEMS "${DEMO}" "${DEMO_RCME}")
    execute_process(COMMAND "${build}" ${ARGS}
      RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT result EQUAL 0)
      message(FATAL_ERROR "${build} did not run to the end (exit '${result}')\n${out}${err}")
    endif()
    if(NOT "${out}" MATCHES "[^\n]*median rotation error[^\n]*")
      message(FATAL_ERROR "${build} printed no summary:\n${out}${err}")
    endif()
    string(APPEND summary "  ${CMAKE_MATCH_0}\n")
  endforeach()
  message(STATUS "both builds finished:\n${summary}")
else()
  message(FATAL_ERROR "unknown MODE '${MODE}'")
endif()
