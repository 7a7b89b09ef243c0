# The 3D view's frames when the renderer cannot be set up (an OpenGL 3.3 context): the view
# shows why, Viewport::glError() holds it and renderError said it once (label gui, Xvfb).
add_test(NAME tst_view_surface_unavailable COMMAND tst_view_surface
         unavailableRendererIsShownInTheView)
set_tests_properties(tst_view_surface_unavailable PROPERTIES LABELS "ui;gui"
  ENVIRONMENT "QT_QPA_PLATFORM=xcb;MESA_GL_VERSION_OVERRIDE=3.3"
  RESOURCE_LOCK x_display_pointer)
