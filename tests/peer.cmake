# The OpenCASCADE mesh peer (issue 10 item 5): `knotwork mesh` and its tagged OBJ against the
# kernel (model label: no GL), and `knotwork render --peer-mesh` against the CPU reference (gl).
kw_add_test(tst_peer_mesh LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_peer_mesh.cpp LIBS knotwork_cad)
target_compile_definitions(tst_peer_mesh PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
kw_use_cad_reader(tst_peer_mesh)
kw_add_test(tst_render_peer LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_peer.cpp LIBS knotwork_cad)
target_compile_definitions(tst_render_peer PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
kw_use_cad_reader(tst_render_peer)
