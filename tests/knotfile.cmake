# .knot project files: round trips, the broken-file corpus, atomic saves, the samples (label model).
kw_add_test(tst_knotfile LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_knotfile.cpp LIBS knotwork_model)
kw_add_test(tst_samples LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_samples.cpp LIBS knotwork_model)
