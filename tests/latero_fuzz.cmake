# Seeded random datagrams against the emulated Latero (tests/latero_fuzz): its decoder and
# model fed directly, then over loopback UDP. Bounded (a few thousand datagrams), repeatable.
tactile_add_test_binary(latero_fuzz_tests latero_fuzz tactile_display)
gtest_discover_tests(latero_fuzz_tests TEST_PREFIX fuzz. PROPERTIES LABELS fuzz
                     DISCOVERY_TIMEOUT 60)
