# The OpenCASCADE mesh peer (issue 10 item 5): `knotwork mesh` and its tagged OBJ against the
# kernel (model label: no GL), and `knotwork render --peer-mesh` against the CPU reference (gl).
kw_add_test(tst_peer_mesh LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_peer_mesh.cpp LIBS knotwork_cad)
target_compile_definitions(tst_peer_mesh PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
kw_use_cad_reader(tst_peer_mesh)
kw_add_test(tst_render_peer LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_peer.cpp LIBS knotwork_cad)
target_compile_definitions(tst_render_peer PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
kw_use_cad_reader(tst_render_peer)
# tools/peer_search.py end to end at 256x256 (its search and relaxation run; seconds): guards the
# lines of `knotwork mesh` and `knotwork render` that it reads.
find_package(Python3 COMPONENTS Interpreter QUIET)
if(Python3_Interpreter_FOUND AND TARGET knotwork_occt_plugin)
  add_test(NAME peer_search_script
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/peer_search.py
                   --knotwork $<TARGET_FILE:knotwork> --work ${KW_TEST_OUTPUT_DIR}/peer_search
                   --size 256 --frames 1 --rounds 1 ${KW_TEST_DATA_DIR}/Pump_Nut.brep)
  set_tests_properties(peer_search_script PROPERTIES LABELS gl TIMEOUT 300
                       PASS_REGULAR_EXPRESSION "\\| Pump_Nut \\| [0-9.e+-]+ / [0-9.]+° \\| [0-9]+ \\| [^\n]* cells \\|"
                       FAIL_REGULAR_EXPRESSION "not reached|Traceback")
endif()
