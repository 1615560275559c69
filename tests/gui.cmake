# The GLFW viewer in a real window: under Xvfb (software GL from Mesa), pixels read back.
# -noreset: Xvfb otherwise resets when the last client leaves and refuses the next test's window.
# The `tactile view` command line is run the same way (view_cli_test.cpp), so the binary waits
# for the program.
tactile_add_test_binary(gui_tests gui tactile_display_viewer)
target_include_directories(gui_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/display)
add_dependencies(gui_tests tactile)
find_program(XVFB_RUN xvfb-run REQUIRED)
add_test(NAME gui.viewer COMMAND ${XVFB_RUN} -a -s "-screen 0 1280x1024x24 -noreset" $<TARGET_FILE:gui_tests>)
set_tests_properties(gui.viewer PROPERTIES LABELS gui TIMEOUT 180)
if(TACTILE_SANITIZE)
  # Mesa's GL driver, loaded with dlopen, keeps allocations LeakSanitizer cannot attribute;
  # leaks are still checked in every other test.
  set_tests_properties(gui.viewer PROPERTIES ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0")
endif()

# `tactile author` driven by real input events (xdotool) in the same kind of server.
find_program(XDOTOOL xdotool REQUIRED)
add_test(NAME gui.author
         COMMAND ${XVFB_RUN} -a -s "-screen 0 1600x1000x24 -noreset" sh
                 ${CMAKE_CURRENT_SOURCE_DIR}/gui/author_window.sh $<TARGET_FILE:tactile>
                 ${CMAKE_CURRENT_BINARY_DIR}/gui-author)
set_tests_properties(gui.author PROPERTIES LABELS gui TIMEOUT 300)
if(TACTILE_SANITIZE)
  set_tests_properties(gui.author PROPERTIES ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0")
endif()
