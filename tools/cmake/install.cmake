# `cmake --install`: the libraries, their public headers and a package configuration, so that
# another program finds them with find_package(tactile) and links tactile::capture,
# tactile::mapping, tactile::display, tactile::perception, tactile::experiments, tactile::common
# and tactile::firmware. The libraries are static: tactileConfig.cmake finds what they link.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(tactile_modules common movie capture display mapping perception experiments)
foreach(module ${tactile_modules})
  set_target_properties(tactile_${module} PROPERTIES EXPORT_NAME ${module})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
set_target_properties(tactile_chart PROPERTIES EXPORT_NAME chart)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/common/chart/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
set_target_properties(tactile_firmware PROPERTIES EXPORT_NAME firmware)
set_target_properties(tactile_hdf5 PROPERTIES EXPORT_NAME hdf5)
set_target_properties(tactile_warnings PROPERTIES EXPORT_NAME warnings)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/firmware/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${PROJECT_BINARY_DIR}/generated/tactile/common/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tactile/common)
target_include_directories(tactile_common PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)

# tactile_warnings travels only as a link-time name of the static libraries (it adds no flags
# to a consumer's own code).
install(TARGETS tactile_common tactile_chart tactile_movie tactile_capture tactile_display tactile_mapping tactile_perception
                tactile_experiments tactile_firmware tactile_hdf5 tactile_warnings
        EXPORT tactileTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT tactileTargets NAMESPACE tactile:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/tactile)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/tactileConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/tactileConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/tactile)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/tactileConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/tactileConfig.cmake ${PROJECT_BINARY_DIR}/tactileConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/tactile)
