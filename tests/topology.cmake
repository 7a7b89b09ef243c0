# The B-rep topology kept on import (model/topology.h): .knot, the CAD hand-over, Document's
# undo (label model).
kw_add_test(tst_topology LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_topology.cpp
            ${CMAKE_CURRENT_LIST_DIR}/topology_fixtures.h LIBS knotwork_cad knotwork_edit)
