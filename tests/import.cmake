# Import branch tests: selection lifetime (label model, no display) and the editor's File ▸
# Import… (label gui, Xvfb: xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -L gui).
kw_add_test(tst_selection_lifetime LABEL model
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_selection_lifetime.cpp
            ${CMAKE_CURRENT_LIST_DIR}/model_fixtures.h LIBS knotwork_model)
kw_add_test(tst_editor_import LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_editor_import.cpp
            LIBS knotwork_ui)
kw_use_cad_reader(tst_editor_import)
