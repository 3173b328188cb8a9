# Locate or build the LAMMPS the plugin is compiled against. Sets LAMMPS_SOURCE_DIR,
# LAMMPS_EXECUTABLE, LAMMPS_HEADER_DIRS and LAMMPS_SIZES (smallbig, bigbig or smallsmall: the
# integer sizes, read from the lmp binary's -h, else from LAMMPS_DIR's CMakeCache.txt). A user's
# own tree wins over the pinned build.
set(LAMMPS_SOURCE_DIR "" CACHE PATH "LAMMPS source tree (with src/ and cmake/) to build the plugin against")
set(LAMMPS_EXECUTABLE "" CACHE FILEPATH "lmp binary built from LAMMPS_SOURCE_DIR with PLUGIN GRANULAR MOLECULE BPM")
set(LAMMPS_DIR "" CACHE PATH "LAMMPS build or install directory (holds lmp); used with LAMMPS_SOURCE_DIR")

# The pinned build is looked up again at every configure (instant once cached), and a change of
# build-lammps.sh (packages, options) re-runs the configure, so an old build directory follows it;
# a LAMMPS_SOURCE_DIR the user gave is kept.
if(NOT LAMMPS_SOURCE_DIR OR LAMMPS_SOURCE_DIR STREQUAL TBAGS_PINNED_SOURCE_DIR)
  # the pinned LAMMPS 4 Feb 2025 (Debian source package, sha256-verified), built once into a cache
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
    ${CMAKE_CURRENT_SOURCE_DIR}/cmake/build-lammps.sh ${CMAKE_CURRENT_SOURCE_DIR}/cmake/fetch-lammps.sh)
  message(STATUS "tbags: locating the pinned LAMMPS build (first time: fetch + build, 5-15 min)")
  tbags_build_once(build-lammps.sh "the pinned LAMMPS"
    "Use your own LAMMPS with -DLAMMPS_SOURCE_DIR=... -DLAMMPS_EXECUTABLE=... instead."
    LAMMPS_SOURCE_DIR LAMMPS_EXECUTABLE)
  set(LAMMPS_SOURCE_DIR "${TBAGS_LAMMPS_SOURCE_DIR}" CACHE PATH "" FORCE)
  set(LAMMPS_EXECUTABLE "${TBAGS_LAMMPS_EXECUTABLE}" CACHE FILEPATH "" FORCE)
  set(TBAGS_PINNED_SOURCE_DIR "${LAMMPS_SOURCE_DIR}" CACHE INTERNAL "the pinned LAMMPS tree (not the user's)")
endif()

if(NOT EXISTS "${LAMMPS_SOURCE_DIR}/src/lammps.h")
  message(FATAL_ERROR "tbags: LAMMPS_SOURCE_DIR=${LAMMPS_SOURCE_DIR} is not a LAMMPS source tree (no src/lammps.h)")
endif()
foreach(_pkg PLUGIN GRANULAR BPM MOLECULE)
  if(NOT EXISTS "${LAMMPS_SOURCE_DIR}/src/${_pkg}")
    message(FATAL_ERROR "tbags: the LAMMPS tree at ${LAMMPS_SOURCE_DIR} has no ${_pkg} package; the plugin needs PLUGIN GRANULAR BPM MOLECULE")
  endif()
endforeach()
if(NOT LAMMPS_EXECUTABLE AND LAMMPS_DIR)
  find_program(LAMMPS_EXECUTABLE NAMES lmp lmp_mpi HINTS ${LAMMPS_DIR} ${LAMMPS_DIR}/bin NO_DEFAULT_PATH)
endif()
if(NOT LAMMPS_EXECUTABLE)
  find_program(LAMMPS_EXECUTABLE NAMES lmp lmp_mpi)
endif()
set(_sizes "")
if(LAMMPS_EXECUTABLE)
  # the binary must have the PLUGIN package, or 'plugin load' does not exist
  execute_process(COMMAND ${LAMMPS_EXECUTABLE} -h OUTPUT_VARIABLE _help ERROR_QUIET TIMEOUT 60)
  string(FIND "${_help}" "Installed packages:" _pos)
  set(_pk "")
  if(_pos GREATER -1)
    string(SUBSTRING "${_help}" ${_pos} -1 _pk)
  endif()
  foreach(_pkg PLUGIN GRANULAR BPM MOLECULE)
    if(_pos LESS 0 OR NOT _pk MATCHES "[ \n]${_pkg}[ \n]")
      message(FATAL_ERROR "tbags: ${LAMMPS_EXECUTABLE} was built without the ${_pkg} package; rebuild LAMMPS with -D PKG_${_pkg}=on or drop -DLAMMPS_EXECUTABLE to use the pinned build")
    endif()
  endforeach()
  # the integer sizes the binary was built with (it prints its -DLAMMPS_<SIZES> define)
  if(_help MATCHES "-DLAMMPS_(SMALLBIG|BIGBIG|SMALLSMALL)")
    string(TOLOWER "${CMAKE_MATCH_1}" _sizes)
  endif()
else()
  message(WARNING "tbags: no lmp binary given (-DLAMMPS_EXECUTABLE=...): the plugin builds, the deck tests are skipped")
endif()
if(NOT _sizes AND LAMMPS_DIR AND EXISTS "${LAMMPS_DIR}/CMakeCache.txt")
  file(STRINGS "${LAMMPS_DIR}/CMakeCache.txt" _line REGEX "^LAMMPS_SIZES:")
  string(REGEX REPLACE "^LAMMPS_SIZES:[A-Z]*=" "" _sizes "${_line}")
endif()
if(NOT _sizes)
  set(_sizes smallbig)
  message(WARNING "tbags: the integer sizes of this LAMMPS are unknown (no lmp to ask, no LAMMPS_DIR): "
    "building for LAMMPS's default, smallbig; give -DLAMMPS_EXECUTABLE=... if yours is bigbig or smallsmall")
endif()
set(LAMMPS_SIZES ${_sizes})
string(TOUPPER "LAMMPS_${_sizes}" LAMMPS_SIZES_DEFINE)
set(LAMMPS_HEADER_DIRS ${LAMMPS_SOURCE_DIR}/src ${LAMMPS_SOURCE_DIR}/src/GRANULAR
    ${LAMMPS_SOURCE_DIR}/src/BPM ${LAMMPS_SOURCE_DIR}/src/MOLECULE ${LAMMPS_SOURCE_DIR}/src/PLUGIN)
message(STATUS "tbags: LAMMPS source ${LAMMPS_SOURCE_DIR}; lmp ${LAMMPS_EXECUTABLE}; integer sizes ${LAMMPS_SIZES}")
