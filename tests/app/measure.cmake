# app tests (label app); a second label says what a test needs: gl, gui or occt.

# `knotwork info --json`: area, volume, bbox and each surface's type (label model).
kw_add_test(tst_info_properties SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_info_properties.cpp
            ${KW_TEST_SUPPORT_DIR}/knotwork_process.h LIBS Qt6::Core)
target_compile_definitions(tst_info_properties PRIVATE KW_KNOTWORK_BIN="$<TARGET_FILE:knotwork>")
add_dependencies(tst_info_properties knotwork)
if(TARGET knotwork_occt_read) # the B-rep case reads a .brep through OpenCASCADE
  target_compile_definitions(tst_info_properties PRIVATE KW_TEST_HAVE_OCCT)
endif()
