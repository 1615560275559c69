# The firmware as a USB device of a real Linux kernel (tests/vm, label vm): the firmware core
# behind a usbredir bridge (vm_harness, host code) on the xHCI controller of a QEMU x86-64
# guest running the installed Debian kernel and a busybox initramfs built here, whose client
# (vm_client) is the project's own USB code: device listing, libusb and hidapi transports,
# player. KVM when a KVM guest boots here, TCG otherwise (below).
find_program(TACTILE_QEMU_X86 qemu-system-x86_64 REQUIRED)
find_program(TACTILE_BUSYBOX busybox PATHS /bin /usr/bin REQUIRED)
find_program(TACTILE_CPIO cpio REQUIRED)
pkg_check_modules(USBREDIRPARSER REQUIRED IMPORTED_TARGET libusbredirparser-0.5)
# The newest installed Debian kernel and its modules (linux-image-amd64).
file(GLOB tactile_vm_kernels /boot/vmlinuz-*)
list(SORT tactile_vm_kernels COMPARE NATURAL)
list(POP_BACK tactile_vm_kernels TACTILE_VM_KERNEL)
if(NOT TACTILE_VM_KERNEL)
  message(FATAL_ERROR "no kernel in /boot: install linux-image-amd64 (tools/setup.sh)")
endif()
string(REGEX REPLACE ".*/vmlinuz-" "" tactile_vm_kernel_version ${TACTILE_VM_KERNEL})
set(TACTILE_VM_MODULES /lib/modules/${tactile_vm_kernel_version})

# The guest client: the display's USB sources compiled again without sanitizers (the guest has
# no sanitizer runtime), linked dynamically; make_initramfs.sh copies the libraries it needs.
set(vm_display_dir ${PROJECT_SOURCE_DIR}/display/src)
file(GLOB vm_firmware_sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/firmware/src/*.c)
add_executable(vm_client ${CMAKE_CURRENT_SOURCE_DIR}/vm/guest/vm_client.cpp
               ${vm_display_dir}/play/player.cpp ${vm_display_dir}/emulator/emulated_device.cpp
               ${vm_display_dir}/transports/frame_codec.cpp
               ${vm_display_dir}/transports/control_codec.cpp
               ${PROJECT_SOURCE_DIR}/movie/src/layouts.cpp ${PROJECT_SOURCE_DIR}/movie/src/limits.cpp
               ${vm_display_dir}/usb/libusb_transport.cpp
               ${vm_display_dir}/usb/hidapi_transport.cpp
               ${vm_display_dir}/usb/devices.cpp ${vm_firmware_sources}
               ${PROJECT_SOURCE_DIR}/common/src/stop_signals.cpp
               ${PROJECT_SOURCE_DIR}/common/src/provenance.cpp
               ${PROJECT_SOURCE_DIR}/common/src/json.cpp)
# common/include for its header-only names.hpp (display's mode enums) and, of common's sources,
# only stop_signals.cpp (the player polls its descriptor) and the provenance (the player and the
# emulated device stamp their output); nothing that needs HDF5.
target_include_directories(vm_client PRIVATE ${PROJECT_SOURCE_DIR}/display/include
                                             ${PROJECT_SOURCE_DIR}/movie/include
                                             ${PROJECT_SOURCE_DIR}/common/include
                                             ${PROJECT_SOURCE_DIR}/firmware/include
                                             ${PROJECT_BINARY_DIR}/generated)
target_link_libraries(vm_client PRIVATE tactile_warnings fmt::fmt nlohmann_json::nlohmann_json
                                        PkgConfig::LIBUSB
                                        PkgConfig::HIDAPI Threads::Threads)
target_compile_options(vm_client PRIVATE -fno-sanitize=all)
target_link_options(vm_client PRIVATE -fno-sanitize=all)

set(vm_dir ${CMAKE_CURRENT_BINARY_DIR}/vm)
set(vm_initrd ${vm_dir}/initramfs.cpio)
file(MAKE_DIRECTORY ${vm_dir})
add_custom_command(
  OUTPUT ${vm_initrd}
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/vm/make_initramfs.sh ${vm_initrd}
          $<TARGET_FILE:vm_client> ${CMAKE_CURRENT_SOURCE_DIR}/vm/guest/init ${TACTILE_VM_MODULES}
          ${TACTILE_BUSYBOX}
  DEPENDS vm_client ${CMAKE_CURRENT_SOURCE_DIR}/vm/make_initramfs.sh
          ${CMAKE_CURRENT_SOURCE_DIR}/vm/initramfs.sh ${CMAKE_CURRENT_SOURCE_DIR}/vm/guest/init
  COMMENT "Building the VM test initramfs (busybox, USB/HID modules, vm_client)"
  VERBATIM)
add_custom_target(vm_initramfs ALL DEPENDS ${vm_initrd})

add_executable(vm_harness ${CMAKE_CURRENT_SOURCE_DIR}/vm/vm_harness.cpp
                          ${CMAKE_CURRENT_SOURCE_DIR}/vm/usbredir_bridge.cpp)
target_include_directories(vm_harness PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/firmware/target)
target_link_libraries(vm_harness PRIVATE tactile_warnings tactile_firmware tactile_common
                                         PkgConfig::USBREDIRPARSER Threads::Threads)
add_dependencies(vm_harness vm_initramfs)

# KVM or TCG is decided once per ctest run: the first vm test boots its guest under KVM (when
# /dev/kvm is there) and falls back to TCG if the guest's init has not printed its first line
# within 20 s (vm_harness.cpp: some hosts offer a /dev/kvm on which a paused start succeeds but
# a guest never boots); the verdict file keeps the outcome for the later tests, which run one
# at a time (RUN_SERIAL below), and it is replaced atomically. The fixture removes the verdict
# of an earlier run first, so each run decides on the machine it runs on.
set(vm_verdict ${vm_dir}/accelerator)
add_test(NAME vm.forget_accelerator COMMAND ${CMAKE_COMMAND} -E rm -f ${vm_verdict})
set_tests_properties(vm.forget_accelerator PROPERTIES LABELS vm FIXTURES_SETUP vm_accelerator)
set(vm_run $<TARGET_FILE:vm_harness> --qemu ${TACTILE_QEMU_X86} --kernel ${TACTILE_VM_KERNEL}
           --initrd ${vm_initrd} --verdict ${vm_verdict})
# One scenario under the sanitizers: the host's side of every scenario (the bridge and the
# firmware core behind it) is the same code, which this scenario and the sanitizer build's
# firmware and usb tests run, and the guest's client is built without them; under TCG each
# scenario boots a guest of its own on one core, one at a time, so the eight more would add
# minutes of emulation to the sanitizer run and no code it does not already check.
add_test(NAME vm.play_libusb COMMAND ${vm_run} play-libusb)
set(vm_usb_tests vm.play_libusb)
if(NOT TACTILE_SANITIZE)
  add_test(NAME vm.enumerate COMMAND ${vm_run} enumerate)
  # The same checks against a bridge that corrupts one descriptor field: they must fail.
  add_test(NAME vm.enumerate_defect COMMAND ${vm_run} --defect enumerate)
  # A 10 x 10 movie for 10 s through the guest kernel (vm.play_libusb above): libusb (vendor
  # bulk) at 700 Hz; hidapi over hidraw at 160 Hz on the full-speed device (hidraw's one report
  # per write sustains about 210 Hz there, below the bus's 250 Hz) and at 500 Hz on a high-speed
  # one; half these rates under TCG (vm_harness.cpp says why).
  # A 4 x 6 display: 64-byte frames, one full packet each, so every frame ends with libusb's
  # zero-length packet, which the guest's xHCI driver sends as a transfer of its own.
  add_test(NAME vm.play_libusb_zlp COMMAND ${vm_run} --grid 4x6 play-libusb)
  add_test(NAME vm.play_hidraw COMMAND ${vm_run} play-hidraw)
  add_test(NAME vm.play_hidraw_high_speed COMMAND ${vm_run} --high-speed play-hidraw)
  # device_del in QEMU's monitor while playing, then the display plugged back in.
  add_test(NAME vm.unplug_replug COMMAND ${vm_run} unplug)
  add_test(NAME vm.unplug_replug_hidraw COMMAND ${vm_run} unplug-hidraw)
  # The fallback on any machine: a KVM guest started paused never reaches its init, so after the
  # bound (5 s here: the bound's value is not what is tested) enumerate runs under TCG and
  # passes, and the verdict file of the other tests is left as it was.
  add_test(NAME vm.kvm_hang_falls_back COMMAND ${vm_run} --kvm-hang --kvm-bound 5 enumerate)
  list(APPEND vm_usb_tests vm.enumerate vm.enumerate_defect vm.play_libusb_zlp vm.play_hidraw
       vm.play_hidraw_high_speed vm.unplug_replug vm.unplug_replug_hidraw vm.kvm_hang_falls_back)
endif()
# Serial: each guest needs a whole core under TCG, and the play tests time a 700 Hz clock.
# The harness stops a guest after 120 s and may run a scenario three times (vm_harness.cpp),
# after a KVM attempt of at most 20 s.
set_tests_properties(${vm_usb_tests} PROPERTIES LABELS vm TIMEOUT 420 RUN_SERIAL TRUE
                                                FIXTURES_REQUIRED vm_accelerator)

# Only in a build without the sanitizers: under TCG the release build's `tactile` in the guest
# already processes only a few frames of a 20 s session; what this test checks is the camera's
# path through a real kernel, and the sanitizers check the session's code in the live e2e tests.
if(NOT TACTILE_SANITIZE)
  # A live session on a real V4L2 camera through the guest's kernel (scenario live-vivid): vivid,
  # the kernel's virtual video driver, loops the frames that v4l2-ctl writes to its HDMI output
  # node into its HDMI capture node, and `tactile live /dev/videoN --headless` reads that node as
  # a camera (guest/init-live). An initramfs of its own: the tactile command's library closure is
  # large, and the USB tests' guest stays as small and quick to boot as it was.
  find_program(TACTILE_V4L2_CTL v4l2-ctl REQUIRED)  # v4l-utils
  find_program(TACTILE_FFMPEG ffmpeg REQUIRED)
  # The frames fed: held-out print 12 under a travelling wave with no slide, turn or exposure
  # drift, 30 frames of 320 x 240 at 47 px/mm, each centred on a 640 x 480 grey field (the
  # smallest HDMI timings vivid offers) as raw BGR24, the capture node's format. Padded, not
  # scaled, so that the print keeps its 47 px/mm. Still skin with a wave under it: the guest
  # processes frames seconds apart, and any two frames of the loop (its wrap included) then differ
  # by a fraction of a pixel, so the landmarks are followed however many frames were dropped
  # between; with the default slide a wrap jumps 12 px and 1.5 degrees, and a guest that processed
  # 35 frames lost every track (median 0 points).
  set(vm_live_frames ${vm_dir}/live-frames.bgr)
  add_custom_command(
    OUTPUT ${vm_live_frames}
    COMMAND ${CMAKE_COMMAND} -E rm -rf ${vm_dir}/live-synth
    COMMAND $<TARGET_FILE:tactile> synth ${vm_dir}/live-synth --from-print
            ${TACTILE_TEST_DATA_DIR}/polyu-hrf-pores/image_12.jpg --px-per-mm 47 --warp wave
            --slide-x 0 --slide-y 0 --turn 0 --drift 0 --frames 30
    COMMAND ${TACTILE_FFMPEG} -nostdin -hide_banner -loglevel error -y -i
            ${vm_dir}/live-synth/frame_%03d.png -vf pad=640:480:160:120:gray -pix_fmt bgr24
            -f rawvideo ${vm_live_frames}
    DEPENDS tactile
    COMMENT "Making the fingerprint frames fed to the live-camera guest (640 x 480 BGR24)"
    VERBATIM)
  set(vm_live_initrd ${vm_dir}/initramfs-live.cpio)
  add_custom_command(
    OUTPUT ${vm_live_initrd}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/vm/make_live_initramfs.sh ${vm_live_initrd}
            $<TARGET_FILE:tactile> ${TACTILE_V4L2_CTL} ${CMAKE_CURRENT_SOURCE_DIR}/vm/guest/init-live
            ${TACTILE_VM_MODULES} ${TACTILE_BUSYBOX} ${vm_live_frames}
    DEPENDS tactile ${vm_live_frames} ${CMAKE_CURRENT_SOURCE_DIR}/vm/make_live_initramfs.sh
            ${CMAKE_CURRENT_SOURCE_DIR}/vm/initramfs.sh
            ${CMAKE_CURRENT_SOURCE_DIR}/vm/guest/init-live
    COMMENT "Building the live-camera VM initramfs (busybox, vivid, v4l2-ctl, tactile, frames)"
    VERBATIM)
  add_custom_target(vm_live_initramfs ALL DEPENDS ${vm_live_initrd})
  add_dependencies(vm_harness vm_live_initramfs)
  set(vm_live_run $<TARGET_FILE:vm_harness> --qemu ${TACTILE_QEMU_X86} --kernel ${TACTILE_VM_KERNEL}
                  --initrd ${vm_live_initrd} --verdict ${vm_verdict})
  # A 20 s session (`tactile live /dev/videoN --px-per-mm 47 --headless --queue-frames 1`), then a
  # 3 s one with the loop off (vivid's colour bars) as the control of the points' floor. Under TCG
  # the guest's CPU processes a frame in seconds, the first (which chooses the pore detector) in
  # 20-80 s, so most of the camera's frames are dropped: what is checked is the camera's path
  # (V4L2 node opened, its format the output's, frames in, the driver's timestamps, the fed
  # frames byte for byte), the fingerprint seen in the frames processed, and exit 0
  # (vm_harness.cpp, check_live). Two vCPUs and 1.5 GB; about 2 min.
  add_test(NAME vm.live_vivid COMMAND ${vm_live_run} --seconds 20 live-vivid)
  set_tests_properties(vm.live_vivid PROPERTIES LABELS vm TIMEOUT 900 RUN_SERIAL TRUE
                                                FIXTURES_REQUIRED vm_accelerator)
endif()
