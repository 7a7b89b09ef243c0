# The exact pass's per-surface data within budget at scale, without GL (label render):
#   ctest --test-dir build -R tst_gpu_budget
kw_add_test(tst_gpu_budget SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_gpu_budget.cpp LIBS knotwork_render)
