# Warnings (and optionally sanitizers) for bodyrec's own targets only; third-party headers come in as
# system includes through their imported targets, so they stay quiet.
function(bodyrec_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  if(BODYREC_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

if(BODYREC_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  # GCC 12 with -fsanitize=address reports false maybe-uninitialized in libstdc++'s <regex> (contour_set.cc),
  # which -Werror turned into a failed `make test-asan` build.
  add_compile_options(-Wno-maybe-uninitialized)
  add_link_options(-fsanitize=address,undefined)
endif()
