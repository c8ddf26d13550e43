# Run by CTest after the discovered GoogleTest list (imucal_tests_TESTS) is loaded: gtest_discover_tests
# gives one set of properties to every test, so the slow suites are picked out here by name.
foreach(t IN LISTS imucal_tests_TESTS)
  if(t MATCHES "^(MonteCarloStudy|Diagnose[A-Za-z]*|Convergence|ImucaldProcess)\\.")
    set_tests_properties("${t}" PROPERTIES LABELS slow)
  endif()
endforeach()
