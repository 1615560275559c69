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

# libFuzzer on every file reader (tests/reader_fuzz): the readers' own sources compiled by clang
# with coverage and sanitizers, linked with the rest of the project's libraries as built. One
# binary; TACTILE_FUZZ_READER picks the reader, `--write-seeds DIR` writes valid seed files.
set(rf_dir ${CMAKE_CURRENT_BINARY_DIR}/reader_fuzz)
set(rf_target ${rf_dir}/reader_fuzz)
set(rf_sources
    tests/reader_fuzz/reader_fuzz.cpp common/src/h5.cpp common/src/json.cpp
    common/src/value_checks.cpp capture/src/strain/strain_movie_io.cpp
    capture/src/camera/calibration_io.cpp capture/src/pores/pore_model_io.cpp
    capture/src/pores/pore_training_io.cpp movie/src/movie_io.cpp movie/src/layout_json.cpp
    movie/src/hjif.cpp
    perception/src/signals/recording_csv.cpp perception/src/learning/classifier_model.cpp
    experiments/src/experiment.cpp)
set(rf_flags -std=c++20 -g -O1 -fsanitize=fuzzer-no-link,address,undefined
             -fno-sanitize-recover=all -DTACTILE_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
foreach(module common capture movie display perception mapping experiments)
  list(APPEND rf_flags -I${PROJECT_SOURCE_DIR}/${module}/include -I${PROJECT_SOURCE_DIR}/${module}/src)
endforeach()
list(APPEND rf_flags -I${PROJECT_BINARY_DIR}/generated -I${PROJECT_SOURCE_DIR}/common/chart/include)
foreach(dir ${HDF5_INCLUDE_DIRS} ${OpenCV_INCLUDE_DIRS})
  list(APPEND rf_flags -isystem ${dir})
endforeach()
set(rf_objects)
foreach(source ${rf_sources})
  string(REPLACE "/" "_" object ${source})
  set(object ${rf_dir}/${object}.o)
  add_custom_command(
    OUTPUT ${object}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${rf_dir}
    COMMAND ${TACTILE_CLANG}++ ${rf_flags} -MD -MF ${object}.d -c ${PROJECT_SOURCE_DIR}/${source}
            -o ${object}
    DEPENDS ${PROJECT_SOURCE_DIR}/${source}
    # Headers too (Ninja reads the compiler's depfile; IMPLICIT_DEPENDS is for Makefiles), so
    # that a struct changed in a header never links against an object of its old layout.
    DEPFILE ${object}.d
    IMPLICIT_DEPENDS CXX ${PROJECT_SOURCE_DIR}/${source}
    COMMENT "Compiling ${source} for the reader fuzzer (clang, libFuzzer + ASan + UBSan)"
    VERBATIM)
  list(APPEND rf_objects ${object})
endforeach()
set(rf_libraries tactile_experiments tactile_perception tactile_capture tactile_movie tactile_common tactile_chart tactile_mapping)
set(rf_library_files)
foreach(lib ${rf_libraries})
  list(APPEND rf_library_files $<TARGET_FILE:${lib}>)
endforeach()
add_custom_command(
  OUTPUT ${rf_target}
  COMMAND ${TACTILE_CLANG}++ -fsanitize=fuzzer,address,undefined ${rf_objects}
          -Wl,--start-group ${rf_library_files} -Wl,--end-group
          ${HDF5_CXX_LIBRARIES} ${HDF5_LIBRARIES} ${PNG_LIBRARIES} ${JPEG_LIBRARIES} -lfmt -lsvm -lcairo -lopencv_imgcodecs
          -lopencv_imgproc -lopencv_core -o ${rf_target}
  DEPENDS ${rf_objects} ${rf_libraries}
  COMMENT "Linking the reader fuzzer"
  VERBATIM)
add_custom_target(reader_fuzz ALL DEPENDS ${rf_target})

# The readers every fuzz run covers. CI runs a fixed seed for a bounded count (repeatable);
# tools/fuzz.sh runs them longer. HDF5 1.10 itself crashes or hangs on some damaged files; the
# movie readers contain that by reading in a child process first, so such a file is a
# FormatError here like any other.
set(TACTILE_FUZZ_READERS strain-movie tactile-movie layout-json hjif calibration-json pore-model-json
                         classifier-model-json recording-csv pore-marks labels-csv experiment-json)
# HDF5 1.10 leaks a few bytes on some damaged files: leak checks only where the library is ours.
# HDF5 asks malloc for whatever size a damaged file declares; outside the sanitizer malloc answers
# NULL and HDF5 reports an error that the reader turns into a FormatError, so the fuzzer lets
# malloc answer NULL too (allocator_may_return_null) instead of stopping on the request.
foreach(reader ${TACTILE_FUZZ_READERS})
  set(leaks 1)
  set(runs 300)
  set(timeout 5)
  if(reader MATCHES "movie$")
    set(leaks 0)
    set(runs 100)
    # Above the reader's own bound for a stalled HDF5 (10 s for a small file): a stall is then
    # the reader's FormatError, not the fuzzer's timeout.
    set(timeout 20)
  endif()
  add_test(NAME fuzz.reader.${reader}
           COMMAND sh -c "rm -rf \"$1/corpus\" \"$1/seeds\" && mkdir -p \"$1/corpus\" \"$1/seeds\" && \"$0\" --write-seeds \"$1/seeds\" && \"$0\" -seed=1 -runs=$3 -detect_leaks=$2 -timeout=$4 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix=\"$1/\" \"$1/corpus\" \"$1/seeds\""
                   ${rf_target} ${rf_dir}/${reader} ${leaks} ${runs} ${timeout})
  set_tests_properties(fuzz.reader.${reader} PROPERTIES LABELS fuzz TIMEOUT 120
                       ENVIRONMENT "TACTILE_FUZZ_READER=${reader};ASAN_OPTIONS=detect_leaks=${leaks}:allocator_may_return_null=1")
endforeach()
