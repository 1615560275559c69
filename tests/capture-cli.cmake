# `tactile evaluate` and `tactile bench capture` on bad input, through the real binary: usage
# errors exit 2, failed runs exit 1 with a message naming the problem (label e2e).
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
capture_cli_expect(synth_rotation_too_large 1 "rotation_deg" synth ${cc_dir}/never
                   --scene flat-rotate --rotation 40 --frames 2)
