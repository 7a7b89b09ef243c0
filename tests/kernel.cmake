# Kernel tests: properties of the NURBS kernel (label kernel, no display needed).
kw_add_test(tst_nurbs_validate LABEL kernel SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_validate.cpp LIBS knotwork_model)
kw_add_test(tst_nurbs_basis LABEL kernel SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_basis.cpp LIBS knotwork_model)
kw_add_test(tst_nurbs_eval LABEL kernel SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_eval.cpp LIBS knotwork_model)
kw_add_test(tst_nurbs_shapes LABEL kernel SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_shapes.cpp LIBS knotwork_model)
kw_add_test(tst_nurbs_modify LABEL kernel SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_modify.cpp LIBS knotwork_model)
kw_add_test(tst_nurbs_curvature LABEL kernel SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_nurbs_curvature.cpp LIBS knotwork_model)
