# USB transports against fake displays on umockdev's testbed (tests/usb): libusb through a fake
# usbdevfs node, hidapi (its hidraw back end, the one the project links) through a fake hidraw
# node; real library code, real firmware behind both. The binary needs umockdev's preload
# library, so it runs through umockdev-wrapper.
pkg_check_modules(UMOCKDEV REQUIRED IMPORTED_TARGET umockdev-1.0)
find_program(TACTILE_UMOCKDEV_WRAPPER umockdev-wrapper REQUIRED)

tactile_add_test_binary(usb_tests usb tactile_display_usb)
target_link_libraries(usb_tests PRIVATE PkgConfig::UMOCKDEV tactile_firmware tactile_live)
target_include_directories(usb_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/firmware/target
                                             ${CMAKE_CURRENT_SOURCE_DIR}/display)
add_test(NAME usb.libusb COMMAND ${TACTILE_UMOCKDEV_WRAPPER} $<TARGET_FILE:usb_tests>
                                 --gtest_filter=UsbLibusb.*)
add_test(NAME usb.hidraw COMMAND ${TACTILE_UMOCKDEV_WRAPPER} $<TARGET_FILE:usb_tests>
                                 --gtest_filter=UsbHidraw.*)
set_tests_properties(usb.libusb usb.hidraw PROPERTIES LABELS usb TIMEOUT 120)
if(TACTILE_SANITIZE)
  # umockdev-wrapper preloads its library ahead of the ASan runtime; the order does not matter
  # here (the preload only forwards system calls), so ASan's check of it is turned off.
  set_tests_properties(usb.libusb usb.hidraw PROPERTIES
                       ENVIRONMENT "ASAN_OPTIONS=detect_leaks=1:verify_asan_link_order=0")
endif()
