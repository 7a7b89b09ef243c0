# Continuity of shared edges (model/continuity.h): the kernel on known cases (label model).
kw_add_test(tst_continuity LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_continuity.cpp
            ${CMAKE_CURRENT_LIST_DIR}/topology_fixtures.h LIBS knotwork_model)
