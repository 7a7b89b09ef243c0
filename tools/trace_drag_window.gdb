# The control-point drag's call stacks as trace_drag.gdb takes them, with the drag's mouse
# events sent to the view's native window itself (what a platform that cannot make the window
# transparent for input delivers there) rather than to the view's widget. Run on Xvfb from the
# build folder:
#   xvfb-run -a -s "-screen 0 1280x1024x24" gdb -batch -x ../tools/trace_drag_window.gdb tests/tst_view_surface
set pagination off
set print frame-arguments none
break kw::ViewSurface::update
disable 1
commands 1
  bt
  disable 1
  continue
end
break kw::Document::changed
commands 2
  bt
  disable 2
  enable 1
  continue
end
break kw::uploadChangedPoints
commands 3
  bt
  disable 3
  continue
end
run inputOnTheNativeWindowIsTheViews
