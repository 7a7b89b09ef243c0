# CAD export's model side (no OCCT): shared edges found for faces without a record.

# model/cad/matchedtopology.h: pairs, gaps, groups taken whole, T-junctions left to sewing.
kw_add_test(tst_matched_topology SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_matched_topology.cpp
            LIBS knotwork_cad)
