# The control-point drag's two call stacks, as docs/ARCHITECTURE.md "An edit's data flow" lists
# them: the move's at the document's write (kw::Document::changed), the frame request it makes
# (kw::ViewSurface::update, armed by the first), and the frame's at the GPU write
# (kw::uploadChangedPoints); one backtrace each. Run on Xvfb from the build folder:
#   xvfb-run -a -s "-screen 0 1280x1024x24" gdb -batch -x ../tools/trace_drag.gdb tests/tst_editor
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
run dragResponsiveness
