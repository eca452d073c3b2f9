# Every dependency is a Debian 12 package; scripts/run.sh installs them (see docs/dependencies.md).
find_package(glm CONFIG REQUIRED)
find_package(nlohmann_json 3.10 CONFIG REQUIRED)
find_package(OpenEXR CONFIG REQUIRED)
find_package(Vulkan REQUIRED COMPONENTS glslangValidator)
find_package(PNG REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(ERFA REQUIRED IMPORTED_TARGET erfa)
list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
find_package(GeographicLib REQUIRED)
if(NOT TARGET GeographicLib::GeographicLib)
  add_library(GeographicLib::GeographicLib INTERFACE IMPORTED)
  target_include_directories(GeographicLib::GeographicLib INTERFACE ${GeographicLib_INCLUDE_DIRS})
  target_link_libraries(GeographicLib::GeographicLib INTERFACE ${GeographicLib_LIBRARIES})
endif()
# OpenVDB (libopenvdb-dev), for clouds/vdb_export.cpp only (`firmament export-vdb`). Debian's
# FindOpenVDB.cmake insists on Boost.Iostreams, which a program linking the shared library does not
# need, so the library and its headers are found directly. Its headers include Boost (libboost-dev:
# headers only), TBB and Imath headers, and code built on them calls into TBB and Imath: both are
# linked through the imported target.
find_path(OpenVDB_INCLUDE_DIR openvdb/openvdb.h)
find_library(OpenVDB_LIBRARY openvdb)
find_path(OpenVDB_BOOST_INCLUDE_DIR boost/any.hpp)
find_package(TBB CONFIG REQUIRED COMPONENTS tbb)
find_package(Imath CONFIG REQUIRED)
if(NOT OpenVDB_INCLUDE_DIR OR NOT OpenVDB_LIBRARY OR NOT OpenVDB_BOOST_INCLUDE_DIR)
  message(FATAL_ERROR "OpenVDB not found (openvdb/openvdb.h: ${OpenVDB_INCLUDE_DIR}, libopenvdb: ${OpenVDB_LIBRARY}, "
                      "boost/any.hpp: ${OpenVDB_BOOST_INCLUDE_DIR}); install libopenvdb-dev and libboost-dev "
                      "(docs/dependencies.md)")
endif()
file(STRINGS ${OpenVDB_INCLUDE_DIR}/openvdb/version.h _openvdb_version
     REGEX "^#define OPENVDB_LIBRARY_(MAJOR|MINOR|PATCH)_VERSION_NUMBER [0-9]+")
string(REGEX REPLACE ".*MAJOR_VERSION_NUMBER ([0-9]+).*MINOR_VERSION_NUMBER ([0-9]+).*PATCH_VERSION_NUMBER ([0-9]+).*"
       "\\1.\\2.\\3" OpenVDB_VERSION "${_openvdb_version}")
message(STATUS "OpenVDB ${OpenVDB_VERSION}: ${OpenVDB_LIBRARY}")
add_library(OpenVDB::openvdb UNKNOWN IMPORTED)
set_target_properties(OpenVDB::openvdb PROPERTIES
  IMPORTED_LOCATION ${OpenVDB_LIBRARY}
  INTERFACE_INCLUDE_DIRECTORIES "${OpenVDB_INCLUDE_DIR};${OpenVDB_BOOST_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES "TBB::tbb;Imath::Imath")
# GDAL (libgdal-dev; Debian 12: 3.6), for terrain/gdal_raster.cpp only: elevation rasters in any format GDAL
# reads. Its CMake config defines GDAL::GDAL; only firmament_terrain_gdal links it.
find_package(GDAL CONFIG)
if(NOT TARGET GDAL::GDAL)
  message(FATAL_ERROR "GDAL not found (its CMake config, GDALConfig.cmake); install libgdal-dev (docs/dependencies.md)")
endif()
message(STATUS "GDAL ${GDAL_VERSION}")
if(FIRMAMENT_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
