# The launcher split (label model): knotwork maps no GUI/GL/OpenImageIO/GLU library, hands the
# drawing commands to knotwork-gl / knotwork-bench, and says so clearly when one is missing.
kw_add_test(tst_launcher LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_launcher.cpp
            LIBS Qt6::Core)
target_compile_definitions(tst_launcher PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>"
                           KW_GL_BIN="$<TARGET_FILE:knotwork_gl>"
                           KW_BENCH_BIN="$<TARGET_FILE:knotwork_bench>")
add_dependencies(tst_launcher knotwork knotwork_bench)
