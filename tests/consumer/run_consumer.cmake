# ctest driver: install the build tree into a scratch prefix, then configure,
# build and run the consumer project against it. A failing step prints its
# command's whole output.
file(REMOVE_RECURSE "${WORK}")
function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc)
    message(FATAL_ERROR "consumer: ${what} failed (${rc}): ${ARGN}\n--- stdout\n${out}\n--- stderr\n${err}")
  endif()
endfunction()
step(install ${CMAKE_COMMAND} --install "${BUILD}" --prefix "${WORK}/prefix")
step(configure ${CMAKE_COMMAND} -S "${SOURCE}" -B "${WORK}/build" -DCMAKE_PREFIX_PATH=${WORK}/prefix
     -DCMAKE_BUILD_TYPE=Release)
step(build ${CMAKE_COMMAND} --build "${WORK}/build")
step(run "${WORK}/build/consumer")
