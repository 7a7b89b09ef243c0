# The B-rep topology kept on import and the seam gaps of edited faces (model/topology.h,
# model/seamgaps.h): .knot, the CAD hand-over, Document's undo, the gap measure (label model).
kw_add_test(tst_topology LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_topology.cpp
            ${CMAKE_CURRENT_LIST_DIR}/topology_fixtures.h LIBS knotwork_cad knotwork_edit)
# The same on the closed solids of tests/data, imported through the CAD child, and
# `knotwork info --json` (needs the knotwork binary).
kw_add_test(tst_topology_import LABEL model
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_topology_import.cpp
            ${CMAKE_CURRENT_LIST_DIR}/knotwork_process.h LIBS knotwork_cad)
target_compile_definitions(tst_topology_import PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
kw_use_cad_reader(tst_topology_import)
