# GL faults in the editor (label gui): shader build failures forced through
# ShaderLibrary::setSourceDirectory, a control net beyond the GPU's texture limit, a destroyed
# and recreated GL context.
kw_add_test(tst_gl_faults LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_gl_faults.cpp
            ${CMAKE_CURRENT_LIST_DIR}/editor_test_util.h LIBS knotwork_ui)
foreach(fault variant init)
  add_test(NAME tst_gl_faults_shader_${fault} COMMAND tst_gl_faults)
  set_tests_properties(tst_gl_faults_shader_${fault} PROPERTIES LABELS gui
    ENVIRONMENT "QT_QPA_PLATFORM=xcb;KW_GL_FAULT=${fault}")
endforeach()
