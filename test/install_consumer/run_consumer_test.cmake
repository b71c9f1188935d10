# cmake -P script: install, configure and build the consumer, run it.
set(prefix "${WORK_DIR}/prefix")
file(REMOVE_RECURSE "${WORK_DIR}")
foreach(step
    "${CMAKE_COMMAND};--install;${RCME_BINARY_DIR};--prefix;${prefix}"
    "${CMAKE_COMMAND};-S;${CONSUMER_SOURCE_DIR};-B;${WORK_DIR}/build;-DCMAKE_PREFIX_PATH=${prefix};-DCMAKE_BUILD_TYPE=Release"
    "${CMAKE_COMMAND};--build;${WORK_DIR}/build"
    "${WORK_DIR}/build/rcme_consumer")
  execute_process(COMMAND ${step} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "consumer test step failed (${result}): ${step}")
  endif()
endforeach()

# The Python module is installed too (when it is built): the installed copy imports, from the
# prefix, with the installed library.
if(PYTHON_EXECUTABLE)
  set(module_dir "${prefix}/${PYTHON_INSTALL_DIR}")
  execute_process(
    COMMAND ${CMAKE_COMMAND} -E env "PYTHONPATH=${module_dir}" "${PYTHON_EXECUTABLE}" -c
      "import rcme, sys; assert rcme.__file__.startswith(sys.argv[1]), rcme.__file__; print(rcme.__file__, rcme.statusToString(rcme.STATUS_SUCCESS))"
      "${module_dir}"
    RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "the installed Python module does not import from ${module_dir}")
  endif()
endif()
