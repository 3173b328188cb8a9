# The second engine: LIGGGHTS-PUBLIC 3.8.0 with our styles compiled in (src-liggghts/ and the
# laws of src-plugin/law/), built once per version, patch set and our sources into the cache by
# cmake/build-liggghts.sh. Sets LIGGGHTS_EXECUTABLE. -DTBAGS_LIGGGHTS=OFF leaves it out (and its
# tests); the sanitized build (TBAGS_SANITIZE) uses a LIGGGHTS built with ASan + UBSan, a tree of
# its own (about 25 min on 2 cores the first time).
option(TBAGS_LIGGGHTS "Build LIGGGHTS-PUBLIC 3.8.0 with the tbags styles and test it" ON)
set(LIGGGHTS_EXECUTABLE "" CACHE FILEPATH "liggghts binary with the tbags styles (set by build-liggghts.sh)")
if(TBAGS_LIGGGHTS)
  set(_asan "")
  if(TBAGS_SANITIZE)
    set(_asan --asan)
  endif()
  message(STATUS "tbags: locating the LIGGGHTS build with our styles ${_asan} (first time: fetch + build, 5-10 min; --asan 25 min)")
  execute_process(COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cmake/build-liggghts.sh ${_asan}
    OUTPUT_VARIABLE _out ERROR_VARIABLE _err RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    string(STRIP "${_err}" _err)
    message(FATAL_ERROR "tbags: could not build LIGGGHTS with our styles:\n${_err}\n"
      "Configure with -DTBAGS_LIGGGHTS=OFF to go on with LAMMPS alone.")
  endif()
  string(REGEX MATCH "LIGGGHTS_EXECUTABLE=([^\n]*)" _m "${_out}")
  set(LIGGGHTS_EXECUTABLE "${CMAKE_MATCH_1}" CACHE FILEPATH "" FORCE)
  # a change of the files the build is keyed on (the script lists them) re-runs the configure,
  # hence the build above
  string(REGEX MATCH "LIGGGHTS_DEPENDS=([^\n]*)" _m "${_out}")
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CMAKE_MATCH_1}
    ${CMAKE_CURRENT_SOURCE_DIR}/cmake/build-liggghts.sh ${CMAKE_CURRENT_SOURCE_DIR}/cmake/fetch-liggghts.sh)
else()
  set(LIGGGHTS_EXECUTABLE "" CACHE FILEPATH "" FORCE)
endif()
