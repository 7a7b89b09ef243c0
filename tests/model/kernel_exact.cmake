# Shape-preserving kernel operations (knot insertion, degree elevation) on the kernel's exact
# quadrics and on real imported rational faces (tests/data/kernel): points, normals, poles.
kw_add_test(tst_nurbs_exact SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_exact.cpp
            ${KW_TEST_SUPPORT_DIR}/kernel_test_util.h LIBS knotwork_model)
