# bench tests (label bench); a second label says what a test needs: gl, gui or occt.

# knotwork bench smoke test (label gl): both tables on one sample at 64x64 for 2 frames; checks
# that the JSON, markdown and PNG plots are well-formed. No timing assertions.
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -R tst_bench
kw_add_test(tst_bench NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bench.cpp LIBS Qt6::Gui)
target_compile_definitions(tst_bench PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_bench knotwork knotwork_bench)
# The scale table: tileScene alone (label model) and a smoke run on hammer.iges at N = 1 and 10
# copies (label gl, the same source with KW_BENCH_RUN).
kw_add_test(tst_scale_scene SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bench_scale.cpp
            ${PROJECT_SOURCE_DIR}/bench/scale_scene.cpp LIBS knotwork_model Qt6::Gui)
kw_add_test(tst_bench_scale NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bench_scale.cpp
            ${PROJECT_SOURCE_DIR}/bench/scale_scene.cpp LIBS knotwork_model Qt6::Gui)
target_compile_definitions(tst_bench_scale PRIVATE KW_BENCH_RUN
                           KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_bench_scale knotwork knotwork_bench)
# The bench uses render's public interface only (no private render header, no Qt OpenGL
# header, no RendererTestHook): tools/check_bench_includes.cmake.
add_test(NAME bench_public_render
         COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -P
                 ${PROJECT_SOURCE_DIR}/tools/check_bench_includes.cmake)
set_tests_properties(bench_public_render PROPERTIES LABELS "bench")
