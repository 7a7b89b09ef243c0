# Face and model properties (area, volume, surface type, bounds), the probe and measurements.
kw_add_test(tst_mass_properties LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_mass_properties.cpp
            LIBS knotwork_model)
# The same against OpenCASCADE's BRepGProp on the source files (labels model and occt).
if(TARGET knotwork_occt_read)
  kw_add_test(tst_mass_occt LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_mass_occt.cpp
              ${KW_TEST_SUPPORT_DIR}/cad_test_util.h LIBS knotwork_occt_read)
  kw_use_cad_reader(tst_mass_occt)
  set_property(TEST tst_mass_occt PROPERTY LABELS model occt)
endif()
# `knotwork info --json`: area, volume, bbox and each surface's type (label model).
kw_add_test(tst_info_properties LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_info_properties.cpp
            ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS Qt6::Core)
target_compile_definitions(tst_info_properties PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_info_properties knotwork)
if(TARGET knotwork_occt_read) # the B-rep case reads a .brep through OpenCASCADE
  target_compile_definitions(tst_info_properties PRIVATE KW_TEST_HAVE_OCCT)
endif()
# The probe's refinement onto the ray, curvature and measurement values (label model).
kw_add_test(tst_probe LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_probe.cpp LIBS knotwork_model)
# The Measure menu in the editor: probe, measure distance, angle and radius, and the Properties
# panel's measured values (label gui, Xvfb).
kw_add_test(tst_measure_gui LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_measure_gui.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
