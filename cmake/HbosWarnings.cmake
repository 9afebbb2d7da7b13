# Warnings and sanitizers are applied per target, never globally, so a parent project that
# add_subdirectory()s hbos keeps its own flags.

# Compressed debug sections (-gz) shrink a RelWithDebInfo build to under half its size for a
# few per cent of build time (README, "Building by hand"): CI builds the tree three times, on a
# disk that has once run out. gdb, valgrind and perf read them. Used only where the compiler
# and linker both accept the flag.
option(HBOS_COMPRESS_DEBUG_INFO "Compress our own targets' debug sections (-gz)" ON)
if(HBOS_COMPRESS_DEBUG_INFO AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang"
   AND NOT DEFINED HBOS_HAVE_GZ)
  include(CheckCXXSourceCompiles)
  set(CMAKE_REQUIRED_FLAGS -gz)
  set(CMAKE_REQUIRED_LINK_OPTIONS -gz)
  check_cxx_source_compiles("int main() { return 0; }" HBOS_HAVE_GZ)
  unset(CMAKE_REQUIRED_FLAGS)
  unset(CMAKE_REQUIRED_LINK_OPTIONS)
endif()
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
  if(HBOS_COMPRESS_DEBUG_INFO AND HBOS_HAVE_GZ)
    target_compile_options(${target} PRIVATE -gz)
    target_link_options(${target} PRIVATE -gz)
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
