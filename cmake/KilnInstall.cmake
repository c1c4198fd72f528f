# `cmake --install` puts the kiln binary, the layer libraries and their headers under the prefix, with a
# find_package(Kiln) config exporting Kiln::kiln_core, Kiln::kiln_materials, Kiln::kiln_lights, Kiln::kiln_scenes,
# Kiln::kiln_accel and Kiln::kiln_renderer.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(_kiln_libs kiln_core kiln_materials kiln_lights kiln_media kiln_scenes kiln_accel kiln_renderer)
install(TARGETS kiln RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The private helper targets carry only link requirements; they are exported so the config resolves.
install(TARGETS kiln_oiio_plugin LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/kiln)
install(TARGETS ${_kiln_libs} kiln_image_libs kiln_tinyobjloader kiln_nanovdb EXPORT KilnTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/kiln)
foreach(_dir core materials lights media scenes renderer)
  install(DIRECTORY ${CMAKE_SOURCE_DIR}/${_dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/kiln/${_dir}
          FILES_MATCHING PATTERN "*.h" PATTERN "bench" EXCLUDE PATTERN "fuzz" EXCLUDE)
endforeach()
install(EXPORT KilnTargets NAMESPACE Kiln:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Kiln)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/KilnConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/KilnConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Kiln)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/KilnConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/KilnConfig.cmake ${CMAKE_BINARY_DIR}/KilnConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Kiln)
