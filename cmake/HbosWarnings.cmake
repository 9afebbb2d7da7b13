# Warnings and sanitizers are applied per target, never globally, so a parent project that
# add_subdirectory()s hbos keeps its own flags.
function(hbos_set_warnings target)
  # An explicit -std=c++17 (not the compiler's gnu++17 default) so that tools reading
  # compile_commands.json, such as clang-tidy, see the same language as the compiler.
  set_target_properties(${target} PROPERTIES CXX_STANDARD 17 CXX_STANDARD_REQUIRED ON
                                             CXX_EXTENSIONS OFF)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE
      -Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wshadow)
    if(HBOS_WERROR)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  endif()
  if(HBOS_SANITIZE)
    # GCC's -Wmaybe-uninitialized gives false positives under the sanitizers' instrumentation
    # (seen in Catch2's own code), so it is not an error in sanitizer builds.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
    endif()
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=all)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()
