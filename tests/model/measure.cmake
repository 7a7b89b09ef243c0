# model tests (label model); a second label says what a test needs: gl, gui or occt.

# Face and model properties (area, volume, surface type, bounds), the probe and measurements.
kw_add_test(tst_mass_properties SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_mass_properties.cpp
            LIBS knotwork_model)
# The same against OpenCASCADE's BRepGProp on the source files (labels model and occt).
if(TARGET knotwork_occt_read)
  kw_add_test(tst_mass_occt NEEDS occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_mass_occt.cpp
              ${KW_TEST_SUPPORT_DIR}/cad_test_util.h LIBS knotwork_occt_read)
  kw_use_cad_reader(tst_mass_occt)
  set_property(TEST tst_mass_occt PROPERTY LABELS "model" occt)
endif()
# The probe's refinement onto the ray, curvature and measurement values (label model).
kw_add_test(tst_probe SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_probe.cpp LIBS knotwork_model)
