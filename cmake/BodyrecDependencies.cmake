# Every dependency comes from Debian packages installed by scripts/install-deps. Also read by the installed
# bodyrecConfig.cmake (with BODYREC_FIND_DEPENDENCY set), so a program built against an installed bodyrec
# finds the same libraries.
if(BODYREC_FIND_DEPENDENCY)
  include(CMakeFindDependencyMacro)
  macro(bodyrec_find_package)
    find_dependency(${ARGN})
  endmacro()
else()
  macro(bodyrec_find_package)
    find_package(${ARGN})
  endmacro()
endif()

# OpenCV: only the modules bodyrec includes, found one by one (Debian's per-module -dev packages; the DPM photo
# detector's module comes from libopencv-contrib-dev), so nothing is linked that no code uses.
set(BODYREC_OPENCV_MODULES core imgproc imgcodecs videoio objdetect video features2d flann dpm)
find_path(BODYREC_OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
foreach(module ${BODYREC_OPENCV_MODULES})
  if(NOT TARGET bodyrec_opencv::${module})
    find_library(BODYREC_OPENCV_${module}_LIBRARY opencv_${module} REQUIRED)
    add_library(bodyrec_opencv::${module} SHARED IMPORTED)
    set_target_properties(bodyrec_opencv::${module} PROPERTIES
      IMPORTED_LOCATION ${BODYREC_OPENCV_${module}_LIBRARY}
      INTERFACE_INCLUDE_DIRECTORIES ${BODYREC_OPENCV_INCLUDE_DIR}
      INTERFACE_SYSTEM_INCLUDE_DIRECTORIES ${BODYREC_OPENCV_INCLUDE_DIR})
  endif()
endforeach()

bodyrec_find_package(dlib REQUIRED)
bodyrec_find_package(SQLite3 REQUIRED)
# A site's shared gallery on PostgreSQL (libpq-dev).
bodyrec_find_package(PostgreSQL REQUIRED)
bodyrec_find_package(nlohmann_json 3 REQUIRED)
bodyrec_find_package(pugixml REQUIRED)
bodyrec_find_package(Threads REQUIRED)
# zlib's crc32: image files are checked before they are decoded (io/image_file.h).
bodyrec_find_package(ZLIB REQUIRED)
bodyrec_find_package(OpenMP REQUIRED COMPONENTS CXX)

# LZF decompression of binary_compressed PCD clouds (liblzf-dev).
find_path(BODYREC_LZF_INCLUDE_DIR liblzf/lzf.h REQUIRED)
find_library(BODYREC_LZF_LIBRARY lzf REQUIRED)
# oneDNN runs the landmark mask network (libdnnl-dev; found by hand because its CMake package also wants the
# OpenCL headers, which bodyrec does not use). It threads with OpenMP; unet_runner.cc calls OpenMP's runtime
# (omp.h needs no -fopenmp), so only its library is linked.
find_path(BODYREC_DNNL_INCLUDE_DIR oneapi/dnnl/dnnl.hpp REQUIRED)
find_library(BODYREC_DNNL_LIBRARY dnnl REQUIRED)
# Events over MQTT (libmosquitto-dev; no CMake package, found by hand).
if(NOT TARGET bodyrec_mosquitto::mosquitto)
  find_path(BODYREC_MOSQUITTO_INCLUDE_DIR mosquitto.h REQUIRED)
  find_library(BODYREC_MOSQUITTO_LIBRARY mosquitto REQUIRED)
  add_library(bodyrec_mosquitto::mosquitto SHARED IMPORTED)
  set_target_properties(bodyrec_mosquitto::mosquitto PROPERTIES
    IMPORTED_LOCATION ${BODYREC_MOSQUITTO_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${BODYREC_MOSQUITTO_INCLUDE_DIR}
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES ${BODYREC_MOSQUITTO_INCLUDE_DIR})
endif()
