# Dependency glue: every dependency comes from a Debian 12 package with a CMake config.
find_package(Threads REQUIRED)
find_package(TBB REQUIRED)
find_package(embree 3 REQUIRED)
find_package(OpenImageIO REQUIRED)  # only for the plugin (renderer/image_io/image_plugin.h)
find_package(OpenEXR 3 REQUIRED)
find_package(PNG REQUIRED)
find_package(pugixml REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(tinyobjloader REQUIRED)
find_package(ZLIB REQUIRED)  # pbrt ".ply.gz" meshes and ".pbrt.gz" includes and ZIP-compressed .nvdb grids
# NanoVDB (media/nanovdb_medium.cpp) is header-only and Debian's libnanovdb-dev ships no CMake config.
find_path(NANOVDB_INCLUDE_DIR nanovdb/NanoVDB.h)
if(NOT NANOVDB_INCLUDE_DIR)
  message(FATAL_ERROR "NanoVDB headers not found (Debian: libnanovdb-dev; .ci/install-deps.sh installs it)")
endif()
add_library(kiln_nanovdb INTERFACE)
target_include_directories(kiln_nanovdb SYSTEM INTERFACE ${NANOVDB_INCLUDE_DIR})
find_package(GTest)
find_package(benchmark QUIET)

# Debian's OpenImageIO config lists /usr/include/opencv4 among its include directories although Kiln never uses
# OpenCV; CMake refuses a non-existent imported include path, so drop it instead of installing OpenCV.
foreach(_tgt OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  if(TARGET ${_tgt})
    get_target_property(_inc ${_tgt} INTERFACE_INCLUDE_DIRECTORIES)
    if(_inc)
      list(FILTER _inc EXCLUDE REGEX "opencv")
      set_target_properties(${_tgt} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_inc}")
    endif()
  endif()
endforeach()
# What the renderer links for images: EXR and PNG directly (a few ms to load), dlopen for the OpenImageIO plugin.
add_library(kiln_image_libs INTERFACE)
target_link_libraries(kiln_image_libs INTERFACE OpenEXR::OpenEXR PNG::PNG ${CMAKE_DL_LIBS})

# Debian ships tinyobjloader under two target names depending on the release.
add_library(kiln_tinyobjloader INTERFACE)
if(TARGET tinyobjloader::tinyobjloader)
  target_link_libraries(kiln_tinyobjloader INTERFACE tinyobjloader::tinyobjloader)
else()
  target_link_libraries(kiln_tinyobjloader INTERFACE tinyobjloader)
endif()
