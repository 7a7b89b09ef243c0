# The exact trimmed area on trims no CAD system writes: loops past the domain, nested or
# crossing loops of any orientation, curves that would make the quadrature run without end.
kw_add_test(tst_hostile_area SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_hostile_area.cpp
            LIBS knotwork_model)
