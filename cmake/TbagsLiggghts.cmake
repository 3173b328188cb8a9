# The second engine: LIGGGHTS-PUBLIC 3.8.0 with our styles compiled in (src-liggghts/ and the
# laws of src-plugin/law/), built once per version, patch set and our sources into the cache by
# cmake/build-liggghts.sh. Sets LIGGGHTS_EXECUTABLE. -DTBAGS_LIGGGHTS=OFF leaves it out (and its
# tests); the sanitized build (TBAGS_SANITIZE) uses a LIGGGHTS built with ASan + UBSan, a tree of
# its own (about 25 min on 2 cores the first time).
option(TBAGS_LIGGGHTS "Build LIGGGHTS-PUBLIC 3.8.0 with the tbags styles and test it" ON)
set(LIGGGHTS_EXECUTABLE "" CACHE FILEPATH "liggghts binary with the tbags styles (set by build-liggghts.sh)")
if(TBAGS_LIGGGHTS)
  message(STATUS "tbags: locating the LIGGGHTS build with our styles (first time: fetch + build, 5-10 min; sanitized 25 min)")
  tbags_build_once(build-liggghts.sh "LIGGGHTS with our styles"
    "Configure with -DTBAGS_LIGGGHTS=OFF to go on with LAMMPS alone."
    LIGGGHTS_EXECUTABLE LIGGGHTS_DEPENDS)
  set(LIGGGHTS_EXECUTABLE "${TBAGS_LIGGGHTS_EXECUTABLE}" CACHE FILEPATH "" FORCE)
  # a change of the files the build is keyed on (the script lists them) re-runs the configure,
  # hence the build above
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${TBAGS_LIGGGHTS_DEPENDS}
    ${CMAKE_CURRENT_SOURCE_DIR}/cmake/build-liggghts.sh ${CMAKE_CURRENT_SOURCE_DIR}/cmake/fetch-liggghts.sh)
else()
  set(LIGGGHTS_EXECUTABLE "" CACHE FILEPATH "" FORCE)
endif()
