# Firmware checks (tests/firmware/target, plain C) on an emulated Cortex-M4: cross-compiled
# with arm-none-eabi-gcc and newlib's rdimon specs (stdio and exit status through
# semihosting), run on QEMU's MPS2+ AN386 board. The host toolchain stays the host's: the
# cross build is a custom command calling the cross compiler directly.
# The same checks also run on the host (label unit) so that a failure can be debugged there.
find_program(TACTILE_ARM_GCC arm-none-eabi-gcc REQUIRED)
find_program(TACTILE_ARM_SIZE arm-none-eabi-size REQUIRED)
find_program(TACTILE_QEMU_ARM qemu-system-arm REQUIRED)

set(fw_dir ${PROJECT_SOURCE_DIR}/firmware)
file(GLOB fw_core_sources CONFIGURE_DEPENDS ${fw_dir}/src/*.c)
file(GLOB fw_check_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/firmware/target/*.c)
file(GLOB fw_headers CONFIGURE_DEPENDS ${fw_dir}/include/tactile_fw/*.h
     ${CMAKE_CURRENT_SOURCE_DIR}/firmware/target/*.h)

add_executable(firmware_checks_host ${fw_check_sources})
target_link_libraries(firmware_checks_host PRIVATE tactile_firmware)
target_compile_options(firmware_checks_host PRIVATE -Wall -Wextra -Wpedantic -Werror)
add_test(NAME firmware.checks_host COMMAND firmware_checks_host)
set_tests_properties(firmware.checks_host PROPERTIES LABELS unit TIMEOUT 60)

set(m4_flags -mcpu=cortex-m4 -mthumb -mfloat-abi=soft -std=c11 -O2 -g -Wall -Wextra -Wpedantic
             -Werror -ffunction-sections -fdata-sections)
set(m4_dir ${CMAKE_CURRENT_BINARY_DIR}/firmware_m4)
set(m4_elf ${m4_dir}/firmware_checks_m4.elf)
# Made at configure time: Makefile generators enter WORKING_DIRECTORY before any COMMAND runs.
file(MAKE_DIRECTORY ${m4_dir})
# The firmware core alone, as objects, so that its own flash and RAM footprint is printed
# (text = flash; data + bss = RAM, almost all of it the frame FIFO).
set(m4_core_objects "")
foreach(src ${fw_core_sources})
  get_filename_component(stem ${src} NAME_WE)
  list(APPEND m4_core_objects ${m4_dir}/${stem}.o)
endforeach()
add_custom_command(
  OUTPUT ${m4_elf} ${m4_core_objects}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${m4_dir}
  COMMAND ${TACTILE_ARM_GCC} ${m4_flags} -I${fw_dir}/include -c ${fw_core_sources}
  COMMAND ${TACTILE_ARM_GCC} ${m4_flags} --specs=rdimon.specs -Wl,--gc-sections
          -T ${fw_dir}/arm/mps2_an386.ld -I${fw_dir}/include ${fw_dir}/arm/startup.c
          ${fw_core_sources} ${fw_check_sources} -o ${m4_elf}
  COMMAND ${CMAKE_COMMAND} -E echo "Cortex-M4 firmware core (text = flash, data + bss = RAM):"
  COMMAND ${TACTILE_ARM_SIZE} -t ${m4_core_objects}
  COMMAND ${CMAKE_COMMAND} -E echo "Cortex-M4 check image (core + checks + newlib):"
  COMMAND ${TACTILE_ARM_SIZE} ${m4_elf}
  WORKING_DIRECTORY ${m4_dir}
  DEPENDS ${fw_core_sources} ${fw_check_sources} ${fw_headers} ${fw_dir}/arm/startup.c
          ${fw_dir}/arm/mps2_an386.ld
  COMMENT "Cross-compiling the firmware checks for Cortex-M4"
  VERBATIM)
add_custom_target(firmware_m4 ALL DEPENDS ${m4_elf})

# QEMU exits with the program's semihosting exit status; a fault spins, and the timeout ends it.
add_test(NAME qemu.firmware_checks
         COMMAND ${TACTILE_QEMU_ARM} -M mps2-an386 -nographic -monitor none -serial null
                 -semihosting -kernel ${m4_elf})
set_tests_properties(qemu.firmware_checks PROPERTIES LABELS qemu TIMEOUT 60)
