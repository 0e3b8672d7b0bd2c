# Included by CTest after the discovered tests are defined (CMakeLists.txt adds it to the
# directory's TEST_INCLUDE_FILES after gtest_discover_tests): gives each test named in
# BLOCKDEM_TEST_COSTS_FILE (CTest's CTestCostData.txt format, one test a line: name, runs,
# seconds) its time as the COST property, so that `ctest -j N` starts the longest tests first,
# on a fresh clone as on a build folder that has run its tests before, and no job is left
# running a long test alone at the end. The times are those of a clean-clone CI run on the
# 2-core machine (tests/costs/); a name not defined here (a test since renamed, or a
# parameterised case whose printed parameter holds an address) is passed over, and a test without
# a time runs after those with one.
if(EXISTS "${BLOCKDEM_TEST_COSTS_FILE}")
  file(STRINGS "${BLOCKDEM_TEST_COSTS_FILE}" blockdem_cost_lines)
  foreach(blockdem_line IN LISTS blockdem_cost_lines)
    if(blockdem_line MATCHES "^(.+) [0-9]+ ([0-9.eE+-]+)$")
      set_tests_properties("${CMAKE_MATCH_1}" PROPERTIES COST "${CMAKE_MATCH_2}")
    endif()
  endforeach()
endif()
