# Analytic faces in closed form (model/nurbs/analytic_eval.h, Surface::analytic).

# The kernel side: forms of the kernel's exact shapes, parameter maps, ray hits, similarities.
kw_add_test(tst_analytic SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_analytic.cpp LIBS knotwork_model)

# The CAD import's side on the analytic parts of tests/data (screw, Pump_Nut, Axis_of_bearing,
# Motor-c): per-kind counts, NURBS = form at random parameters, the form = OCCT's surface, the
# hand-over's encoding, .knot (in process: needs OpenCASCADE, not the knotwork binary).
if(TARGET knotwork_occt_read)
  kw_add_test(tst_analytic_import NEEDS occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_analytic_import.cpp
              LIBS knotwork_occt_read)
endif()

# The document and project-file side: edits drop the form, undo restores it, similarities move
# it, .knot 1.5 round trip, older files, malformed forms.
kw_add_test(tst_analytic_document SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_analytic_document.cpp
            LIBS knotwork_model knotwork_edit)
