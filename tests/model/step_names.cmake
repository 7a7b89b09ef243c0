# STEP names (label model): faces the file leaves unnamed take their product's name.
kw_add_test(tst_step_names SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_step_names.cpp
            LIBS knotwork_cad)
kw_use_cad_reader(tst_step_names)
