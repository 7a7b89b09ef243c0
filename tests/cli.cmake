# The knotwork command line (info, eval): runs the built binary with QProcess (label model).
kw_add_test(tst_cli LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_cli.cpp LIBS knotwork_model)
target_compile_definitions(tst_cli PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_cli knotwork)
