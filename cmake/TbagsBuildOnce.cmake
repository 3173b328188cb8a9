# tbags_build_once(SCRIPT WHAT HINT KEY...): runs cmake/SCRIPT (a build-*.sh that builds an engine
# once into the cache and prints KEY=value lines; --asan when TBAGS_SANITIZE) and sets
# TBAGS_<KEY> in the caller's scope for each KEY asked. On failure: a fatal error naming WHAT,
# the script's message and HINT (the way to go on without it).
function(tbags_build_once script what hint)
  set(_args "")
  if(TBAGS_SANITIZE)
    set(_args --asan)
  endif()
  execute_process(COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cmake/${script} ${_args}
    OUTPUT_VARIABLE _out ERROR_VARIABLE _err RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    string(STRIP "${_err}" _err)
    message(FATAL_ERROR "tbags: could not provide ${what}:\n${_err}\n${hint}")
  endif()
  foreach(_key ${ARGN})
    string(REGEX MATCH "${_key}=([^\n]*)" _m "${_out}")
    set(TBAGS_${_key} "${CMAKE_MATCH_1}" PARENT_SCOPE)
  endforeach()
endfunction()
