# The anisotropic metric checker's known answers (scripts/metricstat.py, numpy): regular tets of
# a metric score 1, and the tensor .sol is read in Medit's component order.
if(EXISTS /usr/bin/python3)
    add_test(NAME metricstat_selftest
             COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/metricstat.py --selftest)
    set_tests_properties(metricstat_selftest PROPERTIES PASS_REGULAR_EXPRESSION "selftest: all passed")
endif()
