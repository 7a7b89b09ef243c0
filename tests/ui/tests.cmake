# ui tests (label ui); a second label says what a test needs: gl, gui or occt.

# The legend and the Colour Range dialog through the real editor window (label gui).
kw_add_test(tst_editor_analysis NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_analysis.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)

# The editor's Open and Import, and `knotwork render` (label gui: Xvfb, the real main window).
kw_add_test(tst_bounds_gui NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_bounds_gui.cpp
            ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS knotwork_ui)
kw_use_cad_reader(tst_bounds_gui)
add_dependencies(tst_bounds_gui kw_failwrite)
target_compile_definitions(tst_bounds_gui PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>"
                           KW_FAILWRITE_LIB="$<TARGET_FILE:kw_failwrite>")

# No cracks while the view moves and while a control point is dragged: the editor's moving
# frames (one renderer across frames, its options and framebuffer) against the CPU reference.
kw_add_test(tst_render_motion NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_motion.cpp
            ${KW_TEST_SUPPORT_DIR}/render_test_util.h ${KW_TEST_SUPPORT_DIR}/cad_test_util.h
            LIBS knotwork_ui)
kw_use_cad_reader(tst_render_motion)
# Closed solids drawn without their polygons' back faces: the same pixels from outside; the eye
# inside, a hidden or an edited face draws them again.
kw_add_test(tst_render_solids NEEDS gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_solids.cpp
            ${KW_TEST_SUPPORT_DIR}/cad_test_util.h ${KW_TEST_SUPPORT_DIR}/image_test_util.h
            LIBS knotwork_ui knotwork_cad Qt6::Gui)
kw_use_cad_reader(tst_render_solids)

# The editor's File ▸ Export… and Save As with a CAD name (label gui, Xvfb).
kw_add_test(tst_editor_export NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_export.cpp
            LIBS knotwork_ui)
kw_use_cad_reader(tst_editor_export)
target_compile_definitions(tst_editor_export PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")

# View › Light Background in the editor, saved with the project (label gui).
kw_add_test(tst_editor_background NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_background.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)

# GL faults in the editor (label gui): shader build failures forced through
# ShaderLibrary::setSourceDirectory, a control net beyond the GPU's texture limit, a destroyed
# and recreated GL context.
kw_add_test(tst_gl_faults NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_gl_faults.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)

# Editor GUI tests (label gui): the real main window under Xvfb (QT_QPA_PLATFORM=xcb), e.g.
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -L gui
kw_add_test(tst_editor NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
kw_add_test(tst_editor_parts SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_parts.cpp
            LIBS knotwork_ui)

kw_add_test(tst_editor_import NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_import.cpp
            LIBS knotwork_ui)
kw_use_cad_reader(tst_editor_import)

kw_add_test(tst_commands SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_commands.cpp
            ${KW_TEST_SUPPORT_DIR}/model_fixtures.h ${KW_TEST_SUPPORT_DIR}/signallog.h
            LIBS knotwork_edit)
kw_add_test(tst_commands_random SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_commands_random.cpp
            ${KW_TEST_SUPPORT_DIR}/model_fixtures.h ${KW_TEST_SUPPORT_DIR}/signallog.h
            LIBS knotwork_edit)

kw_add_test(tst_modeling NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_modeling.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
kw_add_test(tst_modeling_tools NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_modeling_tools.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)

# File > Open Sample finds the samples in the data folder, as the installed editor does.
kw_add_test(tst_samples_menu NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_samples_menu.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)

# Autosave, crash recovery and .bak copies in the editor (label gui: the real main window).
kw_add_test(tst_recovery NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_recovery.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)

# The editor's first minutes: the first window's layout and toolbars, the saved layout at the
# next start, Fit and markers with hidden surfaces, where new shapes appear.
kw_add_test(tst_editor_first_minutes NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_first_minutes.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)

# OverlayBounds: the bounds of what QPainter paints, against the pixels it paints on an image.
kw_add_test(tst_overlay_bounds SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_overlay_bounds.cpp
            LIBS knotwork_ui)
