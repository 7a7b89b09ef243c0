# Modeling (issue 13): kernel constructions and the editor's create / trim / select / place tools.
kw_add_test(tst_nurbs_construct LABEL kernel SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_construct.cpp
            ${CMAKE_CURRENT_LIST_DIR}/kernel_test_util.h LIBS knotwork_model)
kw_add_test(tst_modeling LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_modeling.cpp
            ${CMAKE_CURRENT_LIST_DIR}/editor_test_util.h LIBS knotwork_ui)
kw_add_test(tst_modeling_tools LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_modeling_tools.cpp
            ${CMAKE_CURRENT_LIST_DIR}/editor_test_util.h LIBS knotwork_ui)
