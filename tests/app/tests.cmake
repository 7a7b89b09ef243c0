# app tests (label app); a second label says what a test needs: gl, gui or occt.

# Bounded on every input: non-regular files, slow-reader reproducers, random bytes, a full disk,
# kill -9 and SIGTERM during a CAD read (knotwork as a process), and the checks before OCCT.
kw_add_test(tst_bounds SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bounds.cpp
            ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS knotwork_cad)
add_dependencies(tst_bounds knotwork kw_failwrite)
target_compile_definitions(tst_bounds PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>"
                           KW_FAILWRITE_LIB="$<TARGET_FILE:kw_failwrite>")
set_tests_properties(tst_bounds PROPERTIES TIMEOUT 300)

# knotwork convert as a process (needs the binary); KW_HAVE_OCCT comes with knotwork_cad.
kw_add_test(tst_convert SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_convert.cpp LIBS knotwork_cad)
target_compile_definitions(tst_convert PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_convert knotwork)
set_tests_properties(tst_convert PROPERTIES TIMEOUT 600)
# Reliability (issue 14): reported hostile inputs, the written-files-reopen property over every
# sample, tests/data file and fuzz corpus, kill -9 during convert, the --mesh cap.
kw_add_test(tst_reliability SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_reliability.cpp
            LIBS knotwork_model)
target_compile_definitions(tst_reliability PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_reliability knotwork)
set_tests_properties(tst_reliability PROPERTIES TIMEOUT 1200)
# Each knotwork process takes about a second on a loaded 2-core machine: allow Qt Test more than
# its default 300 s per function for the property test over every input file.
set_property(TEST tst_reliability APPEND PROPERTY ENVIRONMENT QTEST_FUNCTION_TIMEOUT=1100000)
# The OCCT modules, one per format (docs/IMPORT.md): which module and toolkits each read loads.
if(TARGET knotwork_occt_plugin)
  kw_add_test(tst_cad_modules NEEDS occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cad_modules.cpp
              ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS knotwork_cad)
  target_compile_definitions(tst_cad_modules PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
  kw_use_cad_reader(tst_cad_modules)
endif()
# `render FILE.iges` with the CAD child started by the launcher (model/cad/cadprestart.h).
kw_add_test(tst_cad_prestart NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cad_prestart.cpp
            ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS Qt6::Core)
target_compile_definitions(tst_cad_prestart PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_cad_prestart knotwork)

# The knotwork command line (info, eval): runs the built binary with QProcess (label model).
kw_add_test(tst_cli SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cli.cpp LIBS knotwork_model)
target_compile_definitions(tst_cli PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_cli knotwork)

# CAD export (docs/EXCHANGE.md): round trips through STEP and IGES, closed solids, open seams,
# bad destinations; the exported files checked in process with OpenCASCADE.
if(TARGET knotwork_occt_write)
  kw_add_test(tst_exchange NEEDS occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_exchange.cpp
              ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS knotwork_occt_write)
  target_compile_definitions(tst_exchange PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
  kw_use_cad_reader(tst_exchange)
  set_tests_properties(tst_exchange PROPERTIES TIMEOUT 900)
endif()

if(Python3_Interpreter_FOUND)
  add_test(NAME samples_up_to_date COMMAND Python3::Interpreter ${PROJECT_SOURCE_DIR}/tools/make_samples.py --check)
  set_tests_properties(samples_up_to_date PROPERTIES LABELS "app")
endif()

# The launcher split (label model): knotwork maps no GUI/GL/OpenImageIO/GLU library, hands the
# drawing commands to knotwork-gl / knotwork-bench, and says so clearly when one is missing.
kw_add_test(tst_launcher SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_launcher.cpp
            LIBS Qt6::Core)
target_compile_definitions(tst_launcher PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>"
                           KW_GL_BIN="$<TARGET_FILE:knotwork_gl>"
                           KW_BENCH_BIN="$<TARGET_FILE:knotwork_bench>")
add_dependencies(tst_launcher knotwork knotwork_bench)

# Installing (label app): the relocatable install tree, the manual page against --help, and the
# Debian package (also labelled package; it runs where CI runs, as root, and skips elsewhere).
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -L package --output-on-failure
add_test(NAME app_install COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/install_tree.sh
         ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${PROJECT_VERSION})
set_tests_properties(app_install PROPERTIES LABELS "app;gl" TIMEOUT 600)
add_test(NAME app_manpage COMMAND ${CMAKE_COMMAND} -DKNOTWORK=$<TARGET_FILE:knotwork>
         -DMANPAGE=${PROJECT_BINARY_DIR}/packaging/knotwork.1
         -P ${PROJECT_SOURCE_DIR}/tools/check_manpage.cmake)
set_tests_properties(app_manpage PROPERTIES LABELS "app")
add_test(NAME app_package COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/package_deb.sh
         ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${PROJECT_VERSION})
# RUN_SERIAL: apt holds the dpkg lock, and the installed /usr/bin/knotwork should not be seen by
# tests running beside it.
set_tests_properties(app_package PROPERTIES LABELS "app;package" TIMEOUT 900 SKIP_RETURN_CODE 77
                     RUN_SERIAL TRUE)

# The OpenCASCADE mesh peer (issue 10 item 5): `knotwork mesh` and its tagged OBJ against the
# kernel (model label: no GL), and `knotwork render --peer-mesh` against the CPU reference (gl).
kw_add_test(tst_peer_mesh SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_peer_mesh.cpp LIBS knotwork_cad)
target_compile_definitions(tst_peer_mesh PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
kw_use_cad_reader(tst_peer_mesh)
if(Python3_Interpreter_FOUND AND TARGET knotwork_occt_plugin)
  add_test(NAME peer_search_script
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/peer_search.py
                   --knotwork $<TARGET_FILE:knotwork> --work ${KW_TEST_OUTPUT_DIR}/peer_search
                   --size 256 --frames 1 --rounds 1 ${KW_TEST_DATA_DIR}/Pump_Nut.brep)
  set_tests_properties(peer_search_script PROPERTIES LABELS "app;gl" TIMEOUT 300
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
  set_tests_properties(speed_floor_script PROPERTIES LABELS "app;gl" TIMEOUT 300
                       PASS_REGULAR_EXPRESSION "${speed_floor_rows}"
                       FAIL_REGULAR_EXPRESSION "Traceback|speed_floor.py:")
  # Bad --peer arguments are refused with a message before anything is drawn (no display).
  add_test(NAME speed_floor_bad_peer_spec
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/speed_floor.py
                   --work ${KW_TEST_OUTPUT_DIR}/speed_floor_bad ${KW_TEST_DATA_DIR}/Pump_Nut.brep
                   --peer ${KW_TEST_DATA_DIR}/Pump_Nut.brep)
  set_tests_properties(speed_floor_bad_peer_spec PROPERTIES LABELS "app"
                       PASS_REGULAR_EXPRESSION "--peer takes FILE=LINEAR,ANGULAR, not '.*Pump_Nut.brep'")
  add_test(NAME speed_floor_peer_not_timed
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/speed_floor.py
                   --work ${KW_TEST_OUTPUT_DIR}/speed_floor_bad ${KW_TEST_DATA_DIR}/Pump_Nut.brep
                   --peer ${KW_TEST_DATA_DIR}/screw.step=0.1,5)
  set_tests_properties(speed_floor_peer_not_timed PROPERTIES LABELS "app"
                       PASS_REGULAR_EXPRESSION "--peer names a file that is not timed: .*screw.step")
  # A knotwork that prints no frame time (echo stands in) is named, not a Python traceback.
  add_test(NAME speed_floor_no_frame_time
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/speed_floor.py
                   --knotwork echo --work ${KW_TEST_OUTPUT_DIR}/speed_floor_bad
                   ${PROJECT_SOURCE_DIR}/resources/samples/trimmed_plate.knot)
  set_tests_properties(speed_floor_no_frame_time PROPERTIES LABELS "app"
                       PASS_REGULAR_EXPRESSION "echo printed no median frame time: render .*trimmed_plate.knot")
endif()

kw_add_test(tst_cmd_render NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cmd_render.cpp LIBS PkgConfig::OIIO)
target_compile_definitions(tst_cmd_render PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_cmd_render knotwork knotwork_bench)

# knotwork info on trimmed files (a process; needs no display).
kw_add_test(tst_trim_info SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim_info.cpp
            ${KW_TEST_SUPPORT_DIR}/trim_test_util.h LIBS knotwork_model)
target_compile_definitions(tst_trim_info PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_trim_info knotwork)
