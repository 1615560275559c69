# libFuzzer on the firmware's receive path (tests/fuzz): built with clang directly (libFuzzer
# needs clang; the project's own compiler may be gcc), run for a bounded time from a seed
# corpus of valid frames. Any crash, sanitizer report or violated property fails the test.
find_program(TACTILE_CLANG clang REQUIRED)

set(fz_dir ${CMAKE_CURRENT_BINARY_DIR}/fuzz)
set(fz_target ${fz_dir}/frame_fuzz)
set(fz_seeder ${fz_dir}/make_seeds)
file(GLOB fz_fw_sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/firmware/src/*.c)
file(GLOB fz_fw_headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/firmware/include/tactile_fw/*.h)
set(fz_flags -std=c11 -g -O1 -Wall -Wextra -Wpedantic -Werror
             -I${PROJECT_SOURCE_DIR}/firmware/include
             -I${CMAKE_CURRENT_SOURCE_DIR}/firmware/target)
add_custom_command(
  OUTPUT ${fz_target} ${fz_seeder}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${fz_dir}
  COMMAND ${TACTILE_CLANG} ${fz_flags} -fsanitize=fuzzer,address,undefined
          -fno-sanitize-recover=all ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/frame_fuzz.c
          ${fz_fw_sources} -o ${fz_target}
  COMMAND ${TACTILE_CLANG} ${fz_flags} ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/make_seeds.c
          ${fz_fw_sources} -o ${fz_seeder}
  DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/frame_fuzz.c
          ${CMAKE_CURRENT_SOURCE_DIR}/firmware/target/device_config.h ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/make_seeds.c
          ${fz_fw_sources} ${fz_fw_headers}
  COMMENT "Building the firmware frame fuzzer (clang, libFuzzer + ASan + UBSan)"
  VERBATIM)
add_custom_target(firmware_fuzz ALL DEPENDS ${fz_target} ${fz_seeder})

# Fresh corpus directories each run: libFuzzer adds what it finds to the first one.
add_test(NAME fuzz.frame_decoder
         COMMAND sh -c "rm -rf \"$2/corpus\" \"$2/seeds\" && mkdir -p \"$2/corpus\" \"$2/seeds\" && \"$1\" \"$2/seeds\" && \"$0\" -max_total_time=15 -timeout=5 -rss_limit_mb=1024 -print_final_stats=1 -artifact_prefix=\"$2/\" \"$2/corpus\" \"$2/seeds\""
                 ${fz_target} ${fz_seeder} ${fz_dir})
set_tests_properties(fuzz.frame_decoder PROPERTIES LABELS fuzz TIMEOUT 90)
