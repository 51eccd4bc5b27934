# One place for the warning policy: every target of ours calls matforge_target_defaults().
if(MATFORGE_SANITIZE)
  set(MATFORGE_SANITIZER_FLAGS -fsanitize=address,undefined,leak -fno-omit-frame-pointer
      -fno-sanitize-recover=undefined)
endif()

function(matforge_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
    -Wno-sign-conversion -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual)
  if(MATFORGE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(MATFORGE_SANITIZE)
    target_compile_options(${target} PRIVATE ${MATFORGE_SANITIZER_FLAGS})
    target_link_options(${target} PRIVATE ${MATFORGE_SANITIZER_FLAGS})
  endif()
endfunction()
