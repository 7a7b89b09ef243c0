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
  # tools/speed_floor.py end to end at 256x256 (every variant once, the peer too): guards its
  # patched shader copies (they must compile and the anchor must exist) and the lines it reads.
  add_test(NAME speed_floor_script
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/speed_floor.py
                   --knotwork $<TARGET_FILE:knotwork> --work ${KW_TEST_OUTPUT_DIR}/speed_floor
                   --size 256 --frames 1 --rounds 1
                   ${PROJECT_SOURCE_DIR}/resources/samples/trimmed_plate.knot
                   ${KW_TEST_DATA_DIR}/Pump_Nut.brep --peer ${KW_TEST_DATA_DIR}/Pump_Nut.brep=0.06,3.536)
  # One row per model: five times, A / U and **floor / U**; the peer's row adds P, P / A and
  # **P / floor** (a difference of 1-frame times at 256x256 may come out negative).
  # (CMake's regular expressions have no {n} repetition and at most 9 groups.)
  set(t "( \\| [-0-9.]+)+") # times in ms
  set(r "[-0-9.]+×")         # a ratio
  string(CONCAT speed_floor_rows
         "\\| trimmed_plate\\.knot \\| fitted${t} \\| ${r}[^\n]*\n"
         "\\| Pump_Nut\\.brep \\| fitted${t} \\| ${r} \\| \\*\\*${r}\\*\\*"
         "${t} \\| ${r} \\| \\*\\*${r}\\*\\* \\|")
  set_tests_properties(speed_floor_script PROPERTIES LABELS gl TIMEOUT 300
                       PASS_REGULAR_EXPRESSION "${speed_floor_rows}"
                       FAIL_REGULAR_EXPRESSION "Traceback|speed_floor.py:")
  # Bad --peer arguments are refused with a message before anything is drawn (no display).
  add_test(NAME speed_floor_bad_peer_spec
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/speed_floor.py
                   --work ${KW_TEST_OUTPUT_DIR}/speed_floor_bad ${KW_TEST_DATA_DIR}/Pump_Nut.brep
                   --peer ${KW_TEST_DATA_DIR}/Pump_Nut.brep)
  set_tests_properties(speed_floor_bad_peer_spec PROPERTIES LABELS app
                       PASS_REGULAR_EXPRESSION "--peer takes FILE=LINEAR,ANGULAR, not '.*Pump_Nut.brep'")
  add_test(NAME speed_floor_peer_not_timed
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/speed_floor.py
                   --work ${KW_TEST_OUTPUT_DIR}/speed_floor_bad ${KW_TEST_DATA_DIR}/Pump_Nut.brep
                   --peer ${KW_TEST_DATA_DIR}/screw.step=0.1,5)
  set_tests_properties(speed_floor_peer_not_timed PROPERTIES LABELS app
                       PASS_REGULAR_EXPRESSION "--peer names a file that is not timed: .*screw.step")
  # A knotwork that prints no frame time (echo stands in) is named, not a Python traceback.
  add_test(NAME speed_floor_no_frame_time
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/speed_floor.py
                   --knotwork echo --work ${KW_TEST_OUTPUT_DIR}/speed_floor_bad
                   ${PROJECT_SOURCE_DIR}/resources/samples/trimmed_plate.knot)
  set_tests_properties(speed_floor_no_frame_time PROPERTIES LABELS app
                       PASS_REGULAR_EXPRESSION "echo printed no median frame time: render .*trimmed_plate.knot")
endif()
