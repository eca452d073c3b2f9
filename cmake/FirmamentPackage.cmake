# The installable package (docs/api.md, "The CMake package"): `cmake --install` puts the public headers
# (include/firmament/), one static library libfirmament.a and FirmamentConfig.cmake under the prefix;
# find_package(Firmament) then gives the target Firmament::firmament. The library is the public API's
# and every layer under it merged into one archive (ar's MRI script); the SPIR-V is compiled into it
# (firmament_shaders) and the default scene too, so nothing is looked up on disk at run time.
set(firmament_package_libraries firmament_api firmament_sky firmament_terrain_gdal firmament_terrain firmament_clouds
    firmament_atmosphere firmament_gpu firmament_shaders firmament_weather firmament_astro firmament_core)
set(firmament_package_archive ${PROJECT_BINARY_DIR}/package/libfirmament.a)
set(firmament_mri "CREATE ${firmament_package_archive}\n")
foreach(library IN LISTS firmament_package_libraries)
  string(APPEND firmament_mri "ADDLIB $<TARGET_FILE:${library}>\n")
endforeach()
string(APPEND firmament_mri "SAVE\nEND\n")
file(GENERATE OUTPUT ${PROJECT_BINARY_DIR}/package/firmament.mri CONTENT "${firmament_mri}")
add_custom_command(
  OUTPUT ${firmament_package_archive}
  COMMAND ${CMAKE_COMMAND} -E rm -f ${firmament_package_archive}
  COMMAND sh -c "${CMAKE_AR} -M < ${PROJECT_BINARY_DIR}/package/firmament.mri"
  DEPENDS ${firmament_package_libraries} ${PROJECT_BINARY_DIR}/package/firmament.mri
  COMMENT "libfirmament.a: the public API and its layers in one archive"
  VERBATIM)
add_custom_target(firmament_package ALL DEPENDS ${firmament_package_archive})

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
# A sanitizer build's archive needs the sanitizer runtimes in the program that links it.
set(FIRMAMENT_PACKAGE_LINK_OPTIONS "")
if(FIRMAMENT_SANITIZE)
  set(FIRMAMENT_PACKAGE_LINK_OPTIONS "-fsanitize=address,undefined")
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/FirmamentConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/package/FirmamentConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Firmament)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/FirmamentConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${firmament_package_archive} DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(FILES ${PROJECT_SOURCE_DIR}/include/firmament/sky.h ${PROJECT_SOURCE_DIR}/include/firmament/embed.h
              ${PROJECT_SOURCE_DIR}/include/firmament/error.h ${PROJECT_SOURCE_DIR}/include/firmament/image.h
              ${PROJECT_SOURCE_DIR}/include/firmament/atmosphere_lookup.glsl
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/firmament)
install(FILES ${PROJECT_BINARY_DIR}/package/FirmamentConfig.cmake
              ${PROJECT_BINARY_DIR}/package/FirmamentConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Firmament)
