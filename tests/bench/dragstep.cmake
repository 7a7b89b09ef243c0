# knotwork bench --drag-step (label gl): two steps on the teapot sample as read and tiled to 100
# faces at 64 x 64 write the "dragStep" rows, with the overlay on and off (no timing compared).
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -R tst_bench_drag_step
kw_add_test(tst_bench_drag_step NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bench_drag_step.cpp
            LIBS Qt6::Gui)
target_compile_definitions(tst_bench_drag_step PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_bench_drag_step knotwork knotwork_bench)
