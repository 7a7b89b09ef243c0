cmake_minimum_required(VERSION 3.16)
# The benchmark draws only through render's public interface. Fails when a
# bench source includes a render header outside the public list below, an OpenGL header other
# than libGLU's (its NURBS tessellator runs on the CPU and returns triangles), or reaches into
# the renderer's private implementation (the test hook); and when a public header itself includes a private
# render header or Qt's OpenGL headers.
#   cmake -DSOURCE_DIR=<repository> -P tools/check_bench_includes.cmake   (ctest: bench_public_render)
set(public
    renderer.h render_types.h frame_report.h triangle_mesh.h offscreen_renderer.h aov_buffer.h
    image_save.h thread_clock.h
    # AnalysisOptions (RenderOptions' analysis modes) and the CPU colour maps: no GL.
    analysis.h
    # kw::tessellate, the CPU grid tessellation of the fine mesh: plain data, no GL.
    gpu_layout.h
    # The CPU reference frame and the edge metrics the edit loop's equal-quality search uses
    # (as `render --edge-report`): ray casting through the kernel, no GL.
    reference_render.h edge_metrics.h
    # The Edge Continuity overlay's bands (what RenderOptions::edgeBands points to) and their
    # per-edge cache, which the drag step re-makes as the editor does: CPU geometry, no GL.
    edge_bands.h)
set(failures 0)
function(check_file file bench_source)
  file(STRINGS ${file} lines REGEX "^[ \t]*#[ \t]*include|RendererTestHook")
  foreach(line IN LISTS lines)
    if(bench_source AND line MATCHES "RendererTestHook")
      message(SEND_ERROR "${file}: uses RendererTestHook (render's tests only): ${line}")
    elseif(line MATCHES "[\"<]render/([^\">]+)[\">]")
      if(NOT CMAKE_MATCH_1 IN_LIST public)
        message(SEND_ERROR "${file}: includes the private header render/${CMAKE_MATCH_1}")
      endif()
    elseif(line MATCHES "<(QOpenGL[A-Za-z_0-9]*|GL/[a-z0-9_.]+|GLES[^>]*)>")
      if(NOT (bench_source AND CMAKE_MATCH_1 STREQUAL "GL/glu.h"))
        message(SEND_ERROR "${file}: includes the OpenGL header <${CMAKE_MATCH_1}>")
      endif()
    endif()
  endforeach()
endfunction()
file(GLOB sources ${SOURCE_DIR}/bench/*.h ${SOURCE_DIR}/bench/*.cpp)
list(LENGTH sources count)
if(count EQUAL 0)
  message(FATAL_ERROR "no bench sources under ${SOURCE_DIR}/bench")
endif()
foreach(f IN LISTS sources)
  check_file(${f} TRUE)
endforeach()
foreach(h IN LISTS public)
  check_file(${SOURCE_DIR}/render/${h} FALSE)
endforeach()
message(STATUS "bench: ${count} sources use render's public headers only")
