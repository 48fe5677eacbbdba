# ctest driver: `cmake --install` of the build tree into a scratch prefix puts
# the Python package under it (never outside), and the interpreter imports
# it from there and measures with it.
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD}" --prefix "${WORK}/prefix"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc)
  message(FATAL_ERROR "install failed (${rc}):\n${out}\n${err}")
endif()
set(site "${WORK}/prefix/${PYDIR}")
if(NOT EXISTS "${site}/polyvol/__init__.py")
  message(FATAL_ERROR "the package is not under the prefix: ${site}/polyvol\n${out}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${site} ${PYTHON} -c
  "import polyvol; assert polyvol.__file__.startswith('${site}'), polyvol.__file__; print(polyvol.volume([[0,0,0],[1,0,0],[0,1,0],[0,0,1]], [[0,2,1],[0,1,3],[0,3,2],[1,2,3]]))"
  WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc OR NOT out MATCHES "^0.16666666666666666")
  message(FATAL_ERROR "the installed package does not import or measure (${rc}):\n${out}\n${err}")
endif()
