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
  # -O1 -g1 (after the build type's -O2 -g, so they win): still instrumented, with file and line in every
  # report, and about half the compile time. Most of it went into instantiating nlohmann-json, CLI11 and dlib
  # templates at -O2 with full debug information (34 s for one command's file against 18 s); at -O2 -g the
  # sanitizer build took 34 of CI's 90 minutes. dlib's DNN templates in mask_net.cc at -O2 -g even made
  # GCC 12 use 18.7 GB without finishing.
  add_compile_options(-O1 -g1)
  # GCC 12 with -fsanitize=address reports false maybe-uninitialized in libstdc++'s <regex> (contour_set.cc),
  # which -Werror turned into a failed `make test-asan` build.
  add_compile_options(-Wno-maybe-uninitialized)
  add_link_options(-fsanitize=address,undefined)
endif()
