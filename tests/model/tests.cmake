# model tests (label model); a second label says what a test needs: gl, gui or occt.

kw_add_test(tst_cadimport NEEDS occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cadimport.cpp LIBS ${KW_CAD_TEST_LIBS})
kw_use_cad_reader(tst_cadimport)
set_tests_properties(tst_cadimport PROPERTIES TIMEOUT 600)
kw_add_test(tst_trim SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim.cpp LIBS knotwork_model)
kw_add_test(tst_objfile SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_objfile.cpp LIBS knotwork_model)
# The CAD child's binary hand-over: round trip, truncation, corruption (model/cad/handover.h).
kw_add_test(tst_handover SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_handover.cpp
            LIBS knotwork_cad)
# The IGES numbering repair's quick check against its full rebuild.
if(TARGET knotwork_occt_read)
  kw_add_test(tst_igesrepair NEEDS occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_igesrepair.cpp
              LIBS knotwork_occt_read)
endif()

# Partitions and Fit where the face is: trim parameter boxes, trimmed-geometry bounds, fitCamera.
kw_add_test(tst_visible_bounds SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_visible_bounds.cpp LIBS knotwork_model)

# Import branch tests: selection lifetime (label model, no display) and the editor's File ▸
# Import… (label gui, Xvfb: xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -L gui).
kw_add_test(tst_selection_lifetime SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_selection_lifetime.cpp
            ${KW_TEST_SUPPORT_DIR}/model_fixtures.h LIBS knotwork_model)

# Lenient STEP reading: names that are not strings (Rhino's `$`) warn; damaged geometry is refused.
kw_add_test(tst_step_lenient SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_step_lenient.cpp
            LIBS knotwork_cad)
kw_use_cad_reader(tst_step_lenient)

# Kernel tests: properties of the NURBS kernel (label kernel, no display needed).
kw_add_test(tst_nurbs_validate SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_validate.cpp LIBS knotwork_model)
kw_add_test(tst_nurbs_basis SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_basis.cpp LIBS knotwork_model)
kw_add_test(tst_nurbs_eval SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_eval.cpp LIBS knotwork_model)
kw_add_test(tst_nurbs_shapes SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_shapes.cpp LIBS knotwork_model)
kw_add_test(tst_nurbs_modify SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_modify.cpp LIBS knotwork_model)
kw_add_test(tst_nurbs_curvature SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_curvature.cpp LIBS knotwork_model)

# .knot project files: round trips, the broken-file corpus, atomic saves, the samples (label model).
kw_add_test(tst_knotfile SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_knotfile.cpp LIBS knotwork_model)
kw_add_test(tst_samples SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_samples.cpp LIBS knotwork_model)

# Model tests: document, item model, selection and undo commands (label model, no display).
kw_add_test(tst_document SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_document.cpp
            ${KW_TEST_SUPPORT_DIR}/model_fixtures.h ${KW_TEST_SUPPORT_DIR}/signallog.h
            LIBS knotwork_model)
kw_add_test(tst_scenemodel SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_scenemodel.cpp
            ${KW_TEST_SUPPORT_DIR}/model_fixtures.h LIBS knotwork_model knotwork_edit)

# Modeling (issue 13): kernel constructions and the editor's create / trim / select / place tools.
kw_add_test(tst_nurbs_construct SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_construct.cpp
            ${KW_TEST_SUPPORT_DIR}/kernel_test_util.h LIBS knotwork_model)

# The B-rep topology kept on import and the seam gaps of edited faces (model/document/topology.h,
# model/document/seamgaps.h): .knot, the CAD hand-over, Document's undo, the gap measure (label model).
kw_add_test(tst_topology SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_topology.cpp
            ${KW_TEST_SUPPORT_DIR}/topology_fixtures.h LIBS knotwork_cad knotwork_edit)
# The same on the closed solids of tests/data, imported through the CAD child, and
# `knotwork info --json` (needs the knotwork binary).
kw_add_test(tst_topology_import SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_topology_import.cpp
            ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS knotwork_cad)
target_compile_definitions(tst_topology_import PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
kw_use_cad_reader(tst_topology_import)

# Trimmed surfaces (issue 4): messy trim input on the CPU (model), the GPU trim mask against the
# CPU classification (gl), and the CAD importer's faces against OCCT's trims (gl).
kw_add_test(tst_trim_messy SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim_messy.cpp
            ${KW_TEST_SUPPORT_DIR}/trim_test_util.h LIBS knotwork_model)

# kw::Error and kw::Expected, the one error type every module returns.
kw_add_test(tst_error SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_error.cpp LIBS knotwork_model)
