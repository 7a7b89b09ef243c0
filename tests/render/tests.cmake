# render tests (label render); a second label says what a test needs: gl, gui or occt.

# Surface analysis tests: kernel curvature is in kernel.cmake; these need OpenGL 4.5 (label gl).
kw_add_test(tst_render_analysis NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_analysis.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render PkgConfig::OIIO)
kw_add_test(tst_analysis_options SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_analysis_options.cpp LIBS knotwork_render)
kw_add_test(tst_render_environment NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_environment.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
kw_add_test(tst_render_directions NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_directions.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)

# Issue 10 (the true surface at the edges): guaranteed base-polygon bounds (kernel).
kw_add_test(tst_surface_bound SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_surface_bound.cpp LIBS knotwork_render)
# The CPU reference frame against analytic ray casting, and the edge metrics (no GL).
kw_add_test(tst_reference_render SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_reference_render.cpp LIBS knotwork_render)
# knotwork render --reference / --edge-report end to end (label gl: the GPU frame is compared).
kw_add_test(tst_render_edges NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_edges.cpp LIBS Qt6::Gui)
target_compile_definitions(tst_render_edges PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_render_edges knotwork)
# The base polygon over the trim loops' (u, v) box (gl: measured against the CPU reference).
kw_add_test(tst_render_trim_box NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_trim_box.cpp LIBS knotwork_render)
# View-adaptive partitions: the renderer's choice against the CPU's, the bound sampled, and
# re-tessellation only where the required density changed.
kw_add_test(tst_render_adaptive NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_adaptive.cpp LIBS knotwork_render)

# The AOV of a part read back from STEP against the original's (label gl, Xvfb).
if(TARGET knotwork_occt_write)
  kw_add_test(tst_render_exchange NEEDS gl occt SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_exchange.cpp
              ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render knotwork_cad)
  kw_use_cad_reader(tst_render_exchange)
endif()

# What a new user sees first: zebra stripes against their definition, every visible face lit,
# and the automatic colour range of the curvature maps (label gl: OpenGL 4.5).
kw_add_test(tst_render_zebra NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_zebra.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
kw_add_test(tst_render_lighting NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_lighting.cpp
            ${KW_TEST_SUPPORT_DIR}/cad_test_util.h ${KW_TEST_SUPPORT_DIR}/render_test_util.h
            LIBS ${KW_LIGHTING_LIBS})
kw_use_cad_reader(tst_render_lighting)
# The automatic colour range: area-weighted percentiles (no GL).
kw_add_test(tst_analysis_range SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_analysis_range.cpp
            LIBS knotwork_render)
# The background saved with the project (no GL).
kw_add_test(tst_background_setting SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_background_setting.cpp
            LIBS knotwork_render)

foreach(fault variant init)
  add_test(NAME tst_gl_faults_shader_${fault} COMMAND tst_gl_faults)
  set_tests_properties(tst_gl_faults_shader_${fault} PROPERTIES LABELS "render;gui"
    ENVIRONMENT "QT_QPA_PLATFORM=xcb;KW_GL_FAULT=${fault}")
endforeach()

kw_add_test(tst_render_peer NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_peer.cpp LIBS knotwork_cad)
target_compile_definitions(tst_render_peer PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
kw_use_cad_reader(tst_render_peer)

# Render tests (label gl): need an X server with OpenGL 4.5 core, e.g.
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -L gl
kw_add_test(tst_render_layout SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_layout.cpp LIBS knotwork_render)
kw_add_test(tst_render_exact NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_exact.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
kw_add_test(tst_render_baseline NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_baseline.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render PkgConfig::OIIO)
kw_add_test(tst_render_uploads NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_uploads.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
# The exact pass picks the per-cell gather or per-fragment fetches per surface from its cells'
# size on screen; run the AOV-vs-kernel test once more with each variant forced, so both stay
# exact whatever the heuristic picks for the scenes above.
foreach(variant IN ITEMS gather:0 fetch:1e30)
  string(REPLACE ":" ";" parts ${variant})
  list(GET parts 0 name)
  list(GET parts 1 threshold)
  add_test(NAME tst_render_exact_${name} COMMAND tst_render_exact)
  set_tests_properties(tst_render_exact_${name} PROPERTIES LABELS "render;gl"
    ENVIRONMENT "QT_QPA_PLATFORM=xcb;KW_GATHER_MIN_CELL_PX=${threshold}")
endforeach()
kw_add_test(tst_render_scene NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_scene.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
kw_add_test(tst_render_batch NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_batch.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)
kw_add_test(tst_render_incremental NEEDS gl SOURCES
            ${CMAKE_CURRENT_LIST_DIR}/tst_render_incremental.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h LIBS knotwork_render)

# The C++/GLSL contract of the exact pass without GL: the generated shader preamble holds every
# shared constant and no shader repeats one as a literal.
kw_add_test(tst_render_contract SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_contract.cpp
            LIBS knotwork_render)
# The exact pass's planner without GL: variants, culling, batches and in-place patches.
kw_add_test(tst_render_plan SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_plan.cpp
            LIBS knotwork_render)

# Start-up and first image (issue 15 item 6): the trim grid cap `knotwork render` sets from the
# image size changes no pixel. `render FILE.step` itself is tested in tst_cmd_render.
kw_add_test(tst_render_trim_grid_cap NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_trim_grid_cap.cpp
                    ${KW_TEST_SUPPORT_DIR}/render_test_util.h
            LIBS knotwork_render)

kw_add_test(tst_render_trims NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_trims.cpp
            ${KW_TEST_SUPPORT_DIR}/trim_test_util.h ${KW_TEST_SUPPORT_DIR}/render_test_util.h
            LIBS knotwork_render)
set_tests_properties(tst_render_trims PROPERTIES TIMEOUT 900)
kw_add_test(tst_render_cad_coverage NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_cad_coverage.cpp
            ${KW_TEST_SUPPORT_DIR}/trim_test_util.h ${KW_TEST_SUPPORT_DIR}/render_test_util.h
            LIBS ${KW_CAD_COVERAGE_LIBS})
set_tests_properties(tst_render_cad_coverage PROPERTIES TIMEOUT 900)
kw_use_cad_reader(tst_render_cad_coverage)

kw_add_test(tst_render_trims_exact NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_trims_exact.cpp
            ${KW_TEST_SUPPORT_DIR}/trim_test_util.h ${KW_TEST_SUPPORT_DIR}/render_test_util.h
            LIBS ${KW_TRIM_EXACT_GL_LIBS})
set_tests_properties(tst_render_trims_exact PROPERTIES TIMEOUT 900)
kw_use_cad_reader(tst_render_trims_exact)
# Anti-aliased trim edges and silhouettes (issue 11 item 4, gl).
kw_add_test(tst_render_trims_aa NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_trims_aa.cpp
            ${KW_TEST_SUPPORT_DIR}/trim_test_util.h ${KW_TEST_SUPPORT_DIR}/render_test_util.h
            LIBS knotwork_render)

# The hybrid trim grid on the CPU (render/trim_grid.h): arcs, turning points, classification.
kw_add_test(tst_trim_exact SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_trim_exact.cpp
            ${KW_TEST_SUPPORT_DIR}/trim_test_util.h NEEDS occt LIBS knotwork_render ${KW_TRIM_EXACT_LIBS})
set_tests_properties(tst_trim_exact PROPERTIES TIMEOUT 600)
# It imports hammer.iges, which is read by the knotwork binary in a child process.
kw_use_cad_reader(tst_trim_exact)
