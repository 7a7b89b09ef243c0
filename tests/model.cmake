# Model tests: document, item model, selection and undo commands (label model, no display).
kw_add_test(tst_document LABEL model SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_document.cpp
            ${CMAKE_CURRENT_LIST_DIR}/model_fixtures.h ${CMAKE_CURRENT_LIST_DIR}/signallog.h
            LIBS knotwork_model)
