# Included into LAMMPS's own CMake project by build-lammps.sh (CMAKE_PROJECT_INCLUDE): gives the
# lammps library a precompiled header of the LAMMPS and C++ headers nearly every source file
# includes (pointers.h pulls in utils.h and the fmt library). The sources are unchanged; a cold
# build compiles about a third faster (fewer minutes to the first run on a fresh machine).
# Deferred to the end of the top-level CMakeLists, where the lammps target exists.
if(CMAKE_VERSION VERSION_LESS 3.19)    # cmake_language(DEFER) below
  return()
endif()
function(tbags_lammps_pch)
  if(NOT TARGET lammps OR NOT LAMMPS_SOURCE_DIR)
    return()
  endif()
  set(_h "")
  foreach(_f pointers.h utils.h error.h memory.h atom.h comm.h domain.h force.h modify.h neighbor.h
             update.h lammps.h)
    if(EXISTS "${LAMMPS_SOURCE_DIR}/${_f}")
      list(APPEND _h "$<$<COMPILE_LANGUAGE:CXX>:${LAMMPS_SOURCE_DIR}/${_f}>")
    endif()
  endforeach()
  foreach(_s cmath cstring cstdlib string vector map)
    list(APPEND _h "$<$<COMPILE_LANGUAGE:CXX>:<${_s}>>")
  endforeach()
  target_precompile_headers(lammps PRIVATE ${_h})
  message(STATUS "tbags: precompiled header for the lammps library")
endfunction()
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL tbags_lammps_pch)
