# knotwork bench smoke test (label gl): both tables on one sample at 64x64 for 2 frames; checks
# that the JSON, markdown and PNG plots are well-formed. No timing assertions.
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -R tst_bench
kw_add_test(tst_bench LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bench.cpp LIBS Qt6::Gui)
target_compile_definitions(tst_bench PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_bench knotwork)
