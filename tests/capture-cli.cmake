# `tactile evaluate`, `tactile bench capture` and `tactile train-pores` on bad input, through the
# real binary: usage errors exit 2, failed runs exit 1 with a message naming the problem (label
# e2e).
set(cc_dir ${CMAKE_CURRENT_BINARY_DIR}/capture-cli)
set(cc_expect ${CMAKE_CURRENT_SOURCE_DIR}/capture/cli_expect.sh)
set(cc_tactile $<TARGET_FILE:tactile>)

# A tiny synthetic folder, a strain movie measured on it, and files that are not what they say.
add_test(NAME capture_cli.setup
         COMMAND sh -c "rm -rf \"$1\" && mkdir -p \"$1/empty\" && \"$0\" synth \"$1/seq\" --frames 40 && \"$0\" capture \"$1/seq\" --px-per-mm 62 --out \"$1/strain.h5\" --min-track 10 && printf 'not hdf5' > \"$1/fake.h5\""
                 ${cc_tactile} ${cc_dir})
set_tests_properties(capture_cli.setup PROPERTIES LABELS e2e FIXTURES_SETUP capture_cli TIMEOUT 120)

function(capture_cli_expect name code pattern)
  add_test(NAME capture_cli.${name} COMMAND sh ${cc_expect} ${code} ${pattern} ${cc_tactile} ${ARGN})
  set_tests_properties(capture_cli.${name} PROPERTIES LABELS e2e FIXTURES_REQUIRED capture_cli
                       TIMEOUT 120)
endfunction()

capture_cli_expect(evaluate_ok 0 "edge strain RMS error" evaluate ${cc_dir}/seq ${cc_dir}/strain.h5
                   --csv ${cc_dir}/eval)
capture_cli_expect(evaluate_no_args 2 "required" evaluate)
capture_cli_expect(evaluate_missing_dir 2 "Directory does not exist|does not exist" evaluate
                   ${cc_dir}/nowhere ${cc_dir}/strain.h5)
capture_cli_expect(evaluate_not_synth_dir 1 "scene.json" evaluate ${cc_dir}/empty
                   ${cc_dir}/strain.h5)
capture_cli_expect(evaluate_not_hdf5 1 "fake.h5" evaluate ${cc_dir}/seq ${cc_dir}/fake.h5)
capture_cli_expect(bench_too_few_frames 2 "frames" bench capture --frames 5)
capture_cli_expect(features_bad_pores 2 "pores" features ${cc_dir}/seq/frame_000.png
                   --px-per-mm 62 --pores bogus)
capture_cli_expect(features_ridge_blob 0 "features: [0-9]+ pores" features
                   ${cc_dir}/seq/frame_000.png --px-per-mm 62 --pores ridge-blob)
capture_cli_expect(capture_bad_assignment 2 "assignment" capture ${cc_dir}/seq --px-per-mm 62
                   --out ${cc_dir}/never.h5 --assignment bogus)
capture_cli_expect(synth_bad_scene 2 "scene" synth ${cc_dir}/never --scene volcano)
# --rate, the old spelling of --rate-hz: still taken, with a warning, and like it only with
# --from-print.
capture_cli_expect(synth_old_rate_warns 2 "--rate is deprecated" synth ${cc_dir}/never --rate 30)
capture_cli_expect(synth_old_rate_needs_print 2 "--rate requires --from-print" synth ${cc_dir}/never
                   --rate 30)
capture_cli_expect(synth_rotation_too_large 1 "rotation_deg" synth ${cc_dir}/never
                   --scene flat-rotate --rotation 40 --frames 2)

# `tactile train-pores` on 3 of the marked PolyU prints (a few seconds), the model it writes used
# by `tactile features` on a 4th print, and bad input (train_pores_cli.sh builds the folders).
set(tp_dir ${CMAKE_CURRENT_BINARY_DIR}/train-pores-cli)
add_test(NAME train_pores_cli.train
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/capture/train_pores_cli.sh ${cc_tactile}
                 ${TACTILE_TEST_DATA_DIR}/polyu-hrf-pores ${tp_dir})
set_tests_properties(train_pores_cli.train PROPERTIES LABELS e2e FIXTURES_SETUP train_pores_cli
                     TIMEOUT 120)

function(train_pores_cli_expect name code pattern)
  add_test(NAME train_pores_cli.${name}
           COMMAND sh ${cc_expect} ${code} ${pattern} ${cc_tactile} ${ARGN})
  set_tests_properties(train_pores_cli.${name} PROPERTIES LABELS e2e
                       FIXTURES_REQUIRED train_pores_cli TIMEOUT 120)
endfunction()

set(tp_print4 ${TACTILE_TEST_DATA_DIR}/polyu-hrf-pores/image_04.jpg)
# image_04 has 517 marked pores (the shipped model detects 528): a model from 3 other prints
# should find a few hundred.
train_pores_cli_expect(features_with_model 0 "features: [3-6][0-9]{2} pores" features
                       ${tp_print4} --px-per-mm 47 --pores ridge-blob
                       --pore-model ${tp_dir}/model.json)
train_pores_cli_expect(features_with_strict_model 0 "features: 0 pores" features ${tp_print4}
                       --px-per-mm 47 --pores ridge-blob --pore-model ${tp_dir}/strict.json)
train_pores_cli_expect(capture_with_model 0 "capture: 3 frames" capture ${tp_dir}/still
                       --px-per-mm 47 --pores ridge-blob --pore-model ${tp_dir}/model.json
                       --min-track 2 --out ${tp_dir}/still.h5)
train_pores_cli_expect(capture_model_with_paper_rule 2 "pore-model: goes with --pores ridge-blob"
                       capture ${tp_dir}/three --px-per-mm 47 --pores paper
                       --pore-model ${tp_dir}/model.json --out ${tp_dir}/never.h5)
train_pores_cli_expect(out_folder_missing 1 "nowhere: no such folder for --out" train-pores
                       --prints ${tp_dir}/three --px-per-mm 47 --out ${tp_dir}/nowhere/m.json)
train_pores_cli_expect(model_scale_warning 0 "warning: the pore model was trained at 47.0 px/mm"
                       features ${tp_print4} --px-per-mm 60 --pores ridge-blob
                       --pore-model ${tp_dir}/model.json)
train_pores_cli_expect(help_shows_marks 0 "row col" train-pores --help)
train_pores_cli_expect(missing_dir 1 "nowhere: no such directory" train-pores
                       --prints ${tp_dir}/nowhere --px-per-mm 47 --out ${tp_dir}/never.json)
train_pores_cli_expect(empty_dir 1 "empty: no marked prints" train-pores --prints ${tp_dir}/empty
                       --px-per-mm 47 --out ${tp_dir}/never.json)
train_pores_cli_expect(broken_marks 1 "pores_01.txt:2: extra columns" train-pores
                       --prints ${tp_dir}/broken --px-per-mm 47 --out ${tp_dir}/never.json)
train_pores_cli_expect(held_out_one_print 1 "at least 2 prints" train-pores
                       --prints ${tp_dir}/one --px-per-mm 47 --out ${tp_dir}/never.json --held-out)
train_pores_cli_expect(missing_out 2 "--out is required" train-pores --prints ${tp_dir}/three
                       --px-per-mm 47)
train_pores_cli_expect(bad_scale 2 "px-per-mm" train-pores --prints ${tp_dir}/three
                       --px-per-mm abc --out ${tp_dir}/never.json)
train_pores_cli_expect(negative_l2 2 "l2" train-pores --prints ${tp_dir}/three --px-per-mm 47
                       --out ${tp_dir}/never.json --l2 -1)
train_pores_cli_expect(corrupt_model 1 "corrupt.json: not valid JSON" features ${tp_print4}
                       --px-per-mm 47 --pores ridge-blob --pore-model ${tp_dir}/corrupt.json)
# A held-out print that is not in the folder is named before any sequence is rendered: a wrong
# value given (usage, 2), as bench live's --print.
train_pores_cli_expect(bench_prints_unknown_held_out 2 "--held-out 99: .*three holds no print image_99"
                       bench prints ${tp_dir}/three --held-out 99 --out ${tp_dir}/bench-never)
train_pores_cli_expect(model_with_paper_rule 2 "pore-model: goes with --pores ridge-blob"
                       features ${tp_print4} --px-per-mm 47 --pores paper
                       --pore-model ${tp_dir}/model.json)

# `tactile synth --from-print`: a real print moved by an exact warp, captured with the default
# settings (which must pick the ridge-blob detector and refinement on a real print) and scored by
# `tactile evaluate`; and bad input.
set(pw_dir ${CMAKE_CURRENT_BINARY_DIR}/print-warp-cli)
set(pw_print ${TACTILE_TEST_DATA_DIR}/polyu-hrf-pores/image_11.jpg)
add_test(NAME print_warp_cli.setup
         COMMAND sh -c "rm -rf \"$1\" && mkdir -p \"$1/out\" && cp \"$2\" \"$1/out/frame_000.png\" && printf 'not an image' > \"$1/fake.jpg\" && printf '10 10\\n12 x\\n' > \"$1/bad_marks.txt\""
                 ${cc_tactile} ${pw_dir} ${pw_print})
set_tests_properties(print_warp_cli.setup PROPERTIES LABELS e2e FIXTURES_SETUP print_warp_cli)
function(print_warp_cli_expect name code pattern)
  add_test(NAME print_warp_cli.${name} COMMAND sh ${cc_expect} ${code} ${pattern} ${cc_tactile}
                                               ${ARGN})
  set_tests_properties(print_warp_cli.${name} PROPERTIES LABELS e2e
                       FIXTURES_REQUIRED print_warp_cli TIMEOUT 300)
endfunction()
add_test(NAME print_warp_cli.synth_capture_evaluate
         COMMAND sh -c "set -e; \"$0\" synth \"$1/seq\" --from-print \"$2\" --frames 12 --warp bump --strain-pct 6 | grep -E 'from pores_11.txt'; \"$0\" capture \"$1/seq\" --px-per-mm 47 --min-track 10 --out \"$1/s.h5\" | grep -E 'pores: ridge-blob .*refinement|refinement against the images: on' ; \"$0\" evaluate \"$1/seq\" \"$1/s.h5\" | grep -E 'correlation with truth +0[.]9'"
                 ${cc_tactile} ${pw_dir} ${pw_print})
set_tests_properties(print_warp_cli.synth_capture_evaluate PROPERTIES LABELS e2e
                     FIXTURES_REQUIRED print_warp_cli TIMEOUT 300)
print_warp_cli_expect(missing_print 2 "from-print.*(not exist|File does not exist)" synth
                      ${pw_dir}/never --from-print ${pw_dir}/nowhere.jpg)
print_warp_cli_expect(not_an_image 1 "fake.jpg" synth ${pw_dir}/never --from-print
                      ${pw_dir}/fake.jpg)
print_warp_cli_expect(bad_pattern 2 "warp" synth ${pw_dir}/never --from-print ${pw_print}
                      --warp zigzag)
print_warp_cli_expect(strain_out_of_range 2 "strain-pct: 50 is out of range: must be from -20 to 20"
                      synth ${pw_dir}/never --from-print ${pw_print} --strain-pct 50)
print_warp_cli_expect(exposure_over_a_frame 1
                      "exposure_s 0.02 is out of range: must be 0 to one frame \\(0.01667 s\\)"
                      synth ${pw_dir}/never --from-print ${pw_print} --exposure-ms 20 --frames 3)
print_warp_cli_expect(scene_option_with_print 2 "--scene: describes a synthetic scene" synth
                      ${pw_dir}/never --from-print ${pw_print} --scene bump)
print_warp_cli_expect(warp_option_without_print 2 "requires --from-print|from-print" synth
                      ${pw_dir}/never --warp wave)
print_warp_cli_expect(bad_marks 1 "bad_marks.txt:2: expected two numbers" synth ${pw_dir}/never
                      --from-print ${pw_print} --marks ${pw_dir}/bad_marks.txt)
print_warp_cli_expect(out_over_print 2 "OUT_DIR.*--from-print|--from-print.*OUT_DIR" synth
                      ${pw_dir}/out --from-print ${pw_dir}/out/frame_000.png)
print_warp_cli_expect(bench_prints_missing_dir 2 "PRINTS_DIR" bench prints ${pw_dir}/nowhere)
print_warp_cli_expect(bench_prints_no_prints 1 "no marked prints" bench prints ${pw_dir}/out
                      --out ${pw_dir}/bench)
print_warp_cli_expect(bench_prints_bad_frames 2 "--frames: 5 is out of range" bench prints
                      ${pw_dir} --frames 5)
print_warp_cli_expect(bench_prints_small_frame 2 "--frame-px: 8 is out of range" bench prints
                      ${pw_dir} --frame-px 640 8)
print_warp_cli_expect(bench_prints_one_frame_side 2 "--frame-px" bench prints ${pw_dir}
                      --frame-px 640)
