# Lenient STEP reading: names that are not strings (Rhino's `$`) warn; damaged geometry is refused.
kw_add_test(tst_step_lenient LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_step_lenient.cpp
            LIBS knotwork_cad)
kw_use_cad_reader(tst_step_lenient)
