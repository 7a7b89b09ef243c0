# Model tests: document, item model, selection and undo commands (label model, no display).
kw_add_test(tst_document LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_document.cpp
            ${CMAKE_CURRENT_LIST_DIR}/model_fixtures.h ${CMAKE_CURRENT_LIST_DIR}/signallog.h
            LIBS knotwork_model)
kw_add_test(tst_scenemodel LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_scenemodel.cpp
            ${CMAKE_CURRENT_LIST_DIR}/model_fixtures.h LIBS knotwork_model knotwork_edit)
kw_add_test(tst_commands LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_commands.cpp
            ${CMAKE_CURRENT_LIST_DIR}/model_fixtures.h ${CMAKE_CURRENT_LIST_DIR}/signallog.h
            LIBS knotwork_edit)
kw_add_test(tst_commands_random LABEL model
            SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_commands_random.cpp
            ${CMAKE_CURRENT_LIST_DIR}/model_fixtures.h ${CMAKE_CURRENT_LIST_DIR}/signallog.h
            LIBS knotwork_edit)
