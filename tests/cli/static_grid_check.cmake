# Runs hbos-screening-cases --grid static without --fr3 (the static grid composites no one) into
# OUT and compares its two scenes with the committed ones file by file: `static` must be the
# fixture's static scene and `static_reverse` the hold-out's h_static_reverse (the same frames,
# seeds and direction). Used by tests/cli/CMakeLists.txt.
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${GENERATOR}" --grid static --out "${OUT}"
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "hbos-screening-cases --grid static exited with ${rc}:\n${err}")
endif()
foreach(entry "static|${FIXTURE}/static" "static_reverse|${HOLDOUT}/h_static_reverse")
  string(REPLACE "|" ";" entry "${entry}")
  list(GET entry 0 scene)
  list(GET entry 1 committed)
  file(GLOB expected RELATIVE "${committed}" "${committed}/*")
  file(GLOB made RELATIVE "${OUT}/${scene}" "${OUT}/${scene}/*")
  list(SORT expected)
  list(SORT made)
  if(NOT made STREQUAL expected)
    message(FATAL_ERROR "${scene}: files ${made}, the committed scene has ${expected}")
  endif()
  foreach(name IN LISTS expected)
    execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUT}/${scene}/${name}"
                            "${committed}/${name}" RESULT_VARIABLE differs)
    if(NOT differs EQUAL 0)
      message(FATAL_ERROR "${scene}/${name} differs from ${committed}/${name}")
    endif()
  endforeach()
endforeach()
