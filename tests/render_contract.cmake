# The C++/GLSL contract of the exact pass without GL: the generated shader preamble holds every
# shared constant and no shader repeats one as a literal.
kw_add_test(tst_render_contract LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_contract.cpp
            LIBS knotwork_render)
# The exact pass's planner without GL: variants, culling, batches and in-place patches.
kw_add_test(tst_render_plan LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_render_plan.cpp
            LIBS knotwork_render)
