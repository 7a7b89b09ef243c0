# Issue 10 (the true surface at the edges): guaranteed base-polygon bounds (kernel).
kw_add_test(tst_surface_bound LABEL kernel SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_surface_bound.cpp LIBS knotwork_model)
