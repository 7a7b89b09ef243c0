# Bounded on every input: non-regular files, slow-reader reproducers, random bytes, a full disk,
# kill -9 and SIGTERM during a CAD read (knotwork as a process), and the checks before OCCT.
kw_add_test(tst_bounds LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bounds.cpp
            ${CMAKE_CURRENT_LIST_DIR}/knotwork_process.h LIBS knotwork_cad)
# Every write to a folder the test names fails with ENOSPC (LD_PRELOAD), as on a full disk.
add_library(kw_failwrite MODULE ${CMAKE_CURRENT_LIST_DIR}/support/failwrite.cpp)
target_link_libraries(kw_failwrite PRIVATE ${CMAKE_DL_LIBS})
add_dependencies(tst_bounds knotwork kw_failwrite)
target_compile_definitions(tst_bounds PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>"
                           KW_FAILWRITE_LIB="$<TARGET_FILE:kw_failwrite>")
set_tests_properties(tst_bounds PROPERTIES TIMEOUT 300)
# The editor's Open and Import, and `knotwork render` (label gui: Xvfb, the real main window).
kw_add_test(tst_bounds_gui LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bounds_gui.cpp
            ${CMAKE_CURRENT_LIST_DIR}/knotwork_process.h LIBS knotwork_ui)
kw_use_cad_reader(tst_bounds_gui)
add_dependencies(tst_bounds_gui kw_failwrite)
target_compile_definitions(tst_bounds_gui PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>"
                           KW_FAILWRITE_LIB="$<TARGET_FILE:kw_failwrite>")
