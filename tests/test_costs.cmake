# The Catch2 tests that take longest, each with its seconds in a ctest -j2 run of a fresh build (no variant compiled
# yet): ctest starts the costliest first. A fresh build has no record of earlier runs and would otherwise start tests
# in the order they are declared, leaving a long one to run alone at the end while the other core waits. Only the
# order matters; a name that no longer exists is ignored. ctest reads this file after the Catch2 tests' own lists
# (TEST_INCLUDE_FILES); the tests that tests/CMakeLists.txt declares itself get their COST there.
foreach(test_cost
    "order full: generated M and Q equal Lagrange's equations of the quadrature of |r_dot|^2=60"
    "order full at quadrature points equals the expanded form, the Jacobian pieces included=26"
    "generated and assembled agree out of the plane=17"
    "generated Jacobian equals central differences of the right-hand side=15"
    "a tip mass lowers the cantilever's frequencies to the roots of its frequency equation, for every method=12"
    "with rotation and a tip mass the four methods agree as Ny grows=12"
    "generated and assembled agree at a propeller's pre-twist, a radian and more=10")
  string(FIND "${test_cost}" "=" at REVERSE)
  string(SUBSTRING "${test_cost}" 0 ${at} name)
  math(EXPR at "${at} + 1")
  string(SUBSTRING "${test_cost}" ${at} -1 cost)
  set_tests_properties("${name}" PROPERTIES COST ${cost})
endforeach()
