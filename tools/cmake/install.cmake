# `cmake --install`: the libraries, their public headers and a package configuration, so that
# another program finds them with find_package(tactile) and links tactile::capture,
# tactile::mapping, tactile::display (with tactile::display_usb and tactile::display_viewer),
# tactile::perception, tactile::experiments, tactile::common and tactile::firmware. Static libraries (the default): tactileConfig.cmake finds what they link;
# with BUILD_SHARED_LIBS=ON shared ones, each finding the others beside itself ($ORIGIN).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(tactile_modules common movie capture display mapping perception experiments)
# The display's back-end libraries share its header folder; each header goes with the library
# that defines what it declares, so an installation of the display core alone offers nothing
# it cannot link.
set(_tactile_display_usb_headers usb_transports.hpp)
set(_tactile_display_viewer_headers viewer.hpp)
foreach(module ${tactile_modules})
  set_target_properties(tactile_${module} PROPERTIES EXPORT_NAME ${module})
  set(_tactile_excluded "")
  if(module STREQUAL "display")
    foreach(header ${_tactile_display_usb_headers} ${_tactile_display_viewer_headers})
      list(APPEND _tactile_excluded PATTERN ${header} EXCLUDE)
    endforeach()
  endif()
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          COMPONENT ${module} ${_tactile_excluded})
endforeach()
foreach(part usb viewer)
  set_target_properties(tactile_display_${part} PROPERTIES EXPORT_NAME display_${part})
  list(TRANSFORM _tactile_display_${part}_headers
       PREPEND ${PROJECT_SOURCE_DIR}/display/include/tactile/display/)
  install(FILES ${_tactile_display_${part}_headers}
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tactile/display COMPONENT display_${part})
endforeach()
set_target_properties(tactile_chart PROPERTIES EXPORT_NAME chart)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/common/chart/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        COMPONENT chart)
set_target_properties(tactile_firmware PROPERTIES EXPORT_NAME firmware)
set_target_properties(tactile_hdf5 PROPERTIES EXPORT_NAME hdf5)
set_target_properties(tactile_warnings PROPERTIES EXPORT_NAME warnings)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/firmware/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        COMPONENT firmware)
install(FILES ${PROJECT_BINARY_DIR}/generated/tactile/common/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tactile/common COMPONENT common)
target_include_directories(tactile_common PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)

# One export set and one install component per library, so that a library and the ones it uses
# install (`cmake --install B --component movie`, ...) and load without the others having been
# built: tactileConfig.cmake includes the export files of the requested components only.
# tactile_warnings travels only as a link-time name of the static libraries (it adds no flags
# to a consumer's own code); it and tactile_hdf5 go with common.
set(_tactile_targets_of_common tactile_common tactile_hdf5 tactile_warnings)
foreach(module ${tactile_modules} display_usb display_viewer chart firmware)
  if(NOT DEFINED _tactile_targets_of_${module})
    set(_tactile_targets_of_${module} tactile_${module})
  endif()
  install(TARGETS ${_tactile_targets_of_${module}}
          EXPORT tactile_${module}Targets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT ${module}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT ${module})
  install(EXPORT tactile_${module}Targets NAMESPACE tactile::
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/tactile COMPONENT ${module})
endforeach()
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/tactileConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/tactileConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/tactile)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/tactileConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/tactileConfig.cmake ${PROJECT_BINARY_DIR}/tactileConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/tactile COMPONENT common)
