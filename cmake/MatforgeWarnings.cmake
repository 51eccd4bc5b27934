# One place for the warning policy: every target of ours calls matforge_target_defaults().
if(MATFORGE_SANITIZE)
  # -Wmaybe-uninitialized stays a warning there: the sanitizers' instrumentation makes GCC 12
  # report it inside libstdc++ (std::regex's _State moves in <bits/regex_automaton.h>), which
  # the release build, where the flow analysis is exact, keeps an error.
  set(MATFORGE_SANITIZER_FLAGS -fsanitize=address,undefined,leak -fno-omit-frame-pointer
      -fno-sanitize-recover=undefined $<$<CXX_COMPILER_ID:GNU>:-Wno-error=maybe-uninitialized>)
endif()

function(matforge_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
    -Wno-sign-conversion -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual)
  # No code of ours reads errno after a math call or the floating-point exception flags: sqrt
  # becomes one instruction and compare-and-select loops vectorize (the normal-map loops in
  # lib/pack). Values are unchanged: IEEE results do not depend on either.
  target_compile_options(${target} PRIVATE -fno-math-errno -fno-trapping-math)
  if(CMAKE_EXECUTABLE_FORMAT STREQUAL "ELF")
    # The ingest cache's records name the build by this note (core/version.hpp code_identity):
    # asked for, not left to the toolchain's default, and a hash of the output (sha1), never a
    # random uuid, so a reproducible build gets the same one. Stripping keeps it.
    target_link_options(${target} PRIVATE LINKER:--build-id=sha1)
  endif()
  if(MATFORGE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    # GCC 12 at -O3 (a plain Release build) reports -Wrestrict inside libstdc++'s
    # basic_string::insert/replace for `"text" + std::string` (GCC bug 105329, "accessing
    # 9223372036854775810 or more bytes"); GCC 13's libstdc++ silences it at the source. Off for
    # GCC 12 only, so every other -Wall warning stays on in the build users make.
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(CMAKE_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # A unity build includes the .cpp files into one: GCC then takes a struct of one file that
    # holds a type of its anonymous namespace for a header's, which -Wsubobject-linkage is for.
    target_compile_options(${target} PRIVATE -Wno-subobject-linkage)
  endif()
  if(MATFORGE_SANITIZE)
    target_compile_options(${target} PRIVATE ${MATFORGE_SANITIZER_FLAGS})
    target_link_options(${target} PRIVATE ${MATFORGE_SANITIZER_FLAGS})
    # What code asks instead of compiler macros: GCC says __SANITIZE_ADDRESS__, clang
    # __has_feature(address_sanitizer), and the sanitizer build is made with either.
    target_compile_definitions(${target} PRIVATE MATFORGE_SANITIZE_BUILD=1)
  endif()
endfunction()
