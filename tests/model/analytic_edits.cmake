# What an edit of an analytic face costs the document: point, weight, knot and degree edits
# drop the form without a similarity fit (none per drag step), placements fit once, and the
# record kept per face is a few words whatever its net.
kw_add_test(tst_analytic_edits SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_analytic_edits.cpp
            LIBS knotwork_model knotwork_edit)
