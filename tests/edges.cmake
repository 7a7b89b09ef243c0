# Issue 10 (the true surface at the edges): guaranteed base-polygon bounds (kernel).
kw_add_test(tst_surface_bound LABEL kernel SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_surface_bound.cpp LIBS knotwork_model)
# The CPU reference frame against analytic ray casting, and the edge metrics (no GL).
kw_add_test(tst_reference_render LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_reference_render.cpp LIBS knotwork_render)
# knotwork render --reference / --edge-report end to end (label gl: the GPU frame is compared).
kw_add_test(tst_render_edges LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_edges.cpp LIBS Qt6::Gui)
target_compile_definitions(tst_render_edges PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_render_edges knotwork)
# Partitions and Fit where the face is: trim parameter boxes, trimmed-geometry bounds, fitCamera.
kw_add_test(tst_visible_bounds LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_visible_bounds.cpp LIBS knotwork_model)
# The base polygon over the trim loops' (u, v) box (gl: measured against the CPU reference).
kw_add_test(tst_render_trim_box LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_trim_box.cpp LIBS knotwork_render)
# View-adaptive partitions: the renderer's choice against the CPU's, the bound sampled, and
# re-tessellation only where the required density changed.
kw_add_test(tst_render_adaptive LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_adaptive.cpp LIBS knotwork_render)
# No cracks while the view moves and while a control point is dragged: the editor's moving
# frames (one renderer across frames, its options and framebuffer) against the CPU reference.
kw_add_test(tst_render_motion LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_motion.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h ${CMAKE_CURRENT_LIST_DIR}/cad_test_util.h
            LIBS knotwork_ui)
kw_use_cad_reader(tst_render_motion)
# Closed solids drawn without their polygons' back faces: the same pixels from outside; the eye
# inside, a hidden or an edited face draws them again.
kw_add_test(tst_render_solids LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_solids.cpp
            ${CMAKE_CURRENT_LIST_DIR}/cad_test_util.h ${CMAKE_CURRENT_LIST_DIR}/image_test_util.h
            LIBS knotwork_ui knotwork_cad Qt6::Gui)
kw_use_cad_reader(tst_render_solids)
