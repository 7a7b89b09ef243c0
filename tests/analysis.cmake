# Surface analysis tests: kernel curvature is in kernel.cmake; these need OpenGL 4.5 (label gl).
kw_add_test(tst_render_analysis LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_analysis.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render PkgConfig::OIIO)
kw_add_test(tst_analysis_options LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_analysis_options.cpp LIBS knotwork_render)
kw_add_test(tst_render_environment LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_environment.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render)
# The legend and the Colour Range dialog through the real editor window (label gui).
kw_add_test(tst_editor_analysis LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_analysis.cpp
            ${CMAKE_CURRENT_LIST_DIR}/editor_test_util.h LIBS knotwork_ui)
kw_add_test(tst_render_directions LABEL gl SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_directions.cpp
            ${CMAKE_CURRENT_LIST_DIR}/render_test_util.h LIBS knotwork_render)
