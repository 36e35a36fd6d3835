# `cmake --install build --prefix PREFIX`: the `bodyrec` program, the libraries and their headers
# (PREFIX/include/bodyrec/<area>/), the shipped models (PREFIX/share/bodyrec/models), a CMake package
# (find_package(bodyrec) -> bodyrec::bodyrec and bodyrec::<area>) and a pkg-config file (bodyrec.pc).
include(CMakePackageConfigHelpers)
set(BODYREC_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/bodyrec)
install(EXPORT bodyrecTargets NAMESPACE bodyrec:: DESTINATION ${BODYREC_CMAKE_DIR})
configure_package_config_file(cmake/bodyrecConfig.cmake.in ${CMAKE_BINARY_DIR}/bodyrecConfig.cmake
                              INSTALL_DESTINATION ${BODYREC_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/bodyrecConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/bodyrecConfig.cmake ${CMAKE_BINARY_DIR}/bodyrecConfigVersion.cmake
              cmake/BodyrecDependencies.cmake DESTINATION ${BODYREC_CMAKE_DIR})
install(DIRECTORY models/ DESTINATION ${CMAKE_INSTALL_DATADIR}/bodyrec/models)

# pkg-config: the libraries in link order (highest layer first), then what they need.
get_property(areas GLOBAL PROPERTY BODYREC_AREAS)
list(REVERSE areas)
set(BODYREC_PC_LIBS "")
foreach(area ${areas})
  string(APPEND BODYREC_PC_LIBS " -lbodyrec_${area}")
endforeach()
set(BODYREC_PC_OPENCV "")
foreach(module ${BODYREC_OPENCV_MODULES})
  string(APPEND BODYREC_PC_OPENCV " -lopencv_${module}")
endforeach()
string(STRIP "${BODYREC_PC_OPENCV}" BODYREC_PC_OPENCV)
set(BODYREC_PC_OPENNI2 "")
if(BODYREC_WITH_OPENNI2)
  set(BODYREC_PC_OPENNI2 " -lOpenNI2")
endif()
configure_file(cmake/bodyrec.pc.in ${CMAKE_BINARY_DIR}/bodyrec.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/bodyrec.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
