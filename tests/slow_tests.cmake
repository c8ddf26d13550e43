# Run by CTest after the discovered GoogleTest lists (<executable>_TESTS, one per unit test executable named in
# unit_test_targets.cmake) are loaded: gtest_discover_tests gives one set of properties to every test, so the
# slow suites are picked out here by name.
foreach(target IN LISTS imucal_unit_test_targets)
  foreach(t IN LISTS ${target}_TESTS)
    if(t MATCHES "^(MonteCarloStudy|Diagnose[A-Za-z]*|Convergence|ImucaldProcess)\\.")
      set_tests_properties("${t}" PROPERTIES LABELS slow)
    endif()
  endforeach()
endforeach()
