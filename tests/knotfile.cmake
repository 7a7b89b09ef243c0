# .knot project files: round trips, the broken-file corpus, atomic saves, the samples (label model).
kw_add_test(tst_knotfile LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_knotfile.cpp LIBS knotwork_model)
kw_add_test(tst_samples LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_samples.cpp LIBS knotwork_model)
# The committed samples are exactly what tools/make_samples.py generates.
find_package(Python3 COMPONENTS Interpreter)
if(Python3_Interpreter_FOUND)
  add_test(NAME samples_up_to_date COMMAND Python3::Interpreter ${PROJECT_SOURCE_DIR}/tools/make_samples.py --check)
  set_tests_properties(samples_up_to_date PROPERTIES LABELS model)
endif()
