# bench tests (label bench); a second label says what a test needs: gl, gui or occt.

# knotwork bench --edit-loop (label gl, needs the CAD child and its OCCT module): a short drag on
# teapot.igs at 64 x 64 with given peer deflections writes the "editLoop" rows.
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -R tst_bench_edit_loop
if(TARGET knotwork_occt_plugin)
  kw_add_test(tst_bench_edit_loop NEEDS gl occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bench_edit_loop.cpp LIBS Qt6::Gui)
  target_compile_definitions(tst_bench_edit_loop PRIVATE
                             KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
  add_dependencies(tst_bench_edit_loop knotwork knotwork_bench knotwork_occt_plugin)
endif()

# knotwork bench --zoom-loop (label gl, needs the CAD child and its OCCT module): a 4x close-up
# of screw.step at 64 x 64 writes the "zoomLoop" rows.
if(TARGET knotwork_occt_plugin)
  kw_add_test(tst_bench_zoom_loop NEEDS gl occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bench_zoom_loop.cpp LIBS Qt6::Gui)
  target_compile_definitions(tst_bench_zoom_loop PRIVATE
                             KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
  add_dependencies(tst_bench_zoom_loop knotwork knotwork_bench knotwork_occt_plugin)
endif()
