# One static library per folder of src/bodyrec (COLMAP's layout): bodyrec_<area>, alias bodyrec::<area>.
#
#   bodyrec_library(<area> DEPS <areas it may include> [LINK <other PUBLIC libraries>] [PRIVATE <libraries>])
#
# Layering is enforced by the include path: each library's headers are reachable only through a folder of its
# own (<build>/layers/<area>/bodyrec/<area> -> src/bodyrec/<area>) that reaches a target only through DEPS (and
# their DEPS). So `#include "bodyrec/reid/x.h"` in a folder that does not depend on reid fails to compile;
# tests/layering checks that it does.
function(bodyrec_library area)
  cmake_parse_arguments(ARG "" "" "DEPS;LINK;PRIVATE" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  list(FILTER sources EXCLUDE REGEX "_(test|bench)\\.cc$")
  set(target bodyrec_${area})
  add_library(${target} ${sources})
  add_library(bodyrec::${area} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${area} POSITION_INDEPENDENT_CODE ON)
  set(layer ${CMAKE_BINARY_DIR}/layers/${area})
  file(MAKE_DIRECTORY ${layer}/bodyrec)
  file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR} ${layer}/bodyrec/${area} SYMBOLIC)
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${layer}> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  foreach(dep ${ARG_DEPS})
    target_link_libraries(${target} PUBLIC bodyrec_${dep})
  endforeach()
  target_link_libraries(${target} PUBLIC ${ARG_LINK} PRIVATE ${ARG_PRIVATE})
  target_compile_definitions(${target} PUBLIC BODYREC_VERSION="${PROJECT_VERSION}")
  bodyrec_warnings(${target})
  set_property(GLOBAL APPEND PROPERTY BODYREC_AREAS ${area})
  install(TARGETS ${target} EXPORT bodyrecTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  file(GLOB headers CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.h)
  list(FILTER headers EXCLUDE REGEX "_test_support\\.h$")  # tests' helpers are not the library's API
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/bodyrec/${area})
  if(BODYREC_BUILD_TESTS)
    bodyrec_area_tests(${area})
  endif()
endfunction()

# The tests beside an area's code: <area>_test (label unit) from *_test.cc, <area>_data_test (label data,
# needs ../shared/datasets) from *_data_test.cc and <area>_server_test (label server, private PostgreSQL and
# Mosquitto servers, tests/support/server_fixtures.h) from *_server_test.cc, each linked to the area's
# library only. *_suite_test.cc are parameterised suites: they run in the unit program (SQLite) and again in
# the server program (PostgreSQL), which instantiates them.
function(bodyrec_area_tests area)
  file(GLOB unit CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cc)
  file(GLOB data CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_data_test.cc)
  file(GLOB server CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_server_test.cc)
  file(GLOB suites CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_suite_test.cc)
  if(data OR server)
    list(REMOVE_ITEM unit ${data} ${server})
  endif()
  bodyrec_test_exe(${area}_test unit bodyrec_${area} ${unit})
  bodyrec_test_exe(${area}_data_test data bodyrec_${area} ${data})
  if(server)
    bodyrec_test_exe(${area}_server_test server bodyrec_${area} ${server} ${suites})
    target_link_libraries(${area}_server_test PRIVATE bodyrec_test_servers)
  endif()
  if(suites)
    target_link_libraries(${area}_test PRIVATE bodyrec_test_servers)
  endif()
  if(TARGET ${area}_test)
    set_property(GLOBAL APPEND PROPERTY BODYREC_AREA_TESTS ${area}_test)
  endif()
endfunction()

# Per-test time limit. Sanitizer builds get twice the limit.
if(BODYREC_SANITIZE)
  set(BODYREC_TEST_TIMEOUT 3600)
else()
  set(BODYREC_TEST_TIMEOUT 1800)
endif()

# bodyrec_test_exe(<name> <label> <library> <sources...>): one GoogleTest program. A suite listed in
# <name>_ONE_PROCESS runs as one ctest test (all its tests in one process), so a fixture its tests share
# (SetUpTestSuite) is built once instead of once per test; the others are one ctest test each. No skip
# pattern there: one skipped test must not hide a failed one beside it.
function(bodyrec_test_exe name label library)
  set(sources ${ARGN})
  if(NOT sources)
    return()
  endif()
  add_executable(${name} ${sources})
  target_link_libraries(${name} PRIVATE ${library} bodyrec_test_support)
  bodyrec_warnings(${name})
  if(library STREQUAL bodyrec_all)
    add_dependencies(${name} bodyrec)  # the programs under tests/ run the command line; area tests do not
  endif()
  # A program on real servers is one ctest test, so its shared PostgreSQL and Mosquitto start once.
  if(label STREQUAL "server")
    add_test(NAME ${name} COMMAND ${name})
    set_tests_properties(${name} PROPERTIES LABELS "${label}" TIMEOUT ${BODYREC_TEST_TIMEOUT})
    return()
  endif()
  set(excluded "")
  foreach(suite ${${name}_ONE_PROCESS})
    add_test(NAME ${suite}.AllInOneProcess COMMAND ${name} --gtest_filter=${suite}.*)
    set_tests_properties(${suite}.AllInOneProcess PROPERTIES LABELS "${label}" TIMEOUT ${BODYREC_TEST_TIMEOUT})
    list(APPEND excluded "${suite}.*")
  endforeach()
  set(filter "")
  if(excluded)
    list(JOIN excluded ":" joined)
    set(filter TEST_FILTER "-${joined}")
  endif()
  gtest_discover_tests(${name}
    DISCOVERY_TIMEOUT 60 ${filter}
    PROPERTIES LABELS "${label}" SKIP_REGULAR_EXPRESSION "\\[  SKIPPED \\]" TIMEOUT ${BODYREC_TEST_TIMEOUT})
endfunction()
