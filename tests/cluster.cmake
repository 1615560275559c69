# `tactile experiment --slurm` on a real single-node Slurm cluster that each test starts and stops
# itself (tests/cluster/cluster.sh: munged, slurmctld, slurmd from Debian's packages, loopback
# only). A cluster that cannot start fails the test with the reason; it is never skipped.
foreach(mode grid resubmit)
  add_test(NAME cluster.experiment_${mode}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cluster/experiment_test.sh
                   $<TARGET_FILE:tactile> ${mode})
  set_tests_properties(cluster.experiment_${mode} PROPERTIES LABELS cluster TIMEOUT 180)
endforeach()
