# The 3D view's native window and its QOpenGLWidget fallback (ui/view_surface.h; label gui,
# Xvfb). The tools and the probe once more on the fallback (KNOTWORK_VIEW=widget).
kw_add_test(tst_view_surface NEEDS gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_view_surface.cpp
            ${KW_TEST_SUPPORT_DIR}/editor_test_util.h LIBS knotwork_ui)
foreach(test tst_tools tst_measure_gui)
  add_test(NAME ${test}_widget_view COMMAND ${test})
  set_tests_properties(${test}_widget_view PROPERTIES LABELS "ui;gui"
    ENVIRONMENT "QT_QPA_PLATFORM=xcb;KNOTWORK_VIEW=widget" RESOURCE_LOCK x_display_pointer)
endforeach()
