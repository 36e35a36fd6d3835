# cmake -DBUILD_DIR=... -P check.cmake: the allowed include builds; the include against the layers fails to
# compile because the header is not found.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target layering_allowed
                RESULT_VARIABLE allowed OUTPUT_VARIABLE allowed_out ERROR_VARIABLE allowed_out)
if(NOT allowed EQUAL 0)
  message(FATAL_ERROR "the allowed include did not build:\n${allowed_out}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target layering_violation
                RESULT_VARIABLE violation OUTPUT_VARIABLE violation_out ERROR_VARIABLE violation_out)
if(violation EQUAL 0)
  message(FATAL_ERROR "an include against the layers (store -> reid) compiled")
endif()
if(NOT violation_out MATCHES "bodyrec/reid/partial_scan.h: No such file")
  message(FATAL_ERROR "the violation failed for another reason:\n${violation_out}")
endif()
message(STATUS "layering enforced: store cannot include reid")
