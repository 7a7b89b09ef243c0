# The document's change list (Document::changesSince), which the renderer pulls at frame time
# (label model, no display).
kw_add_test(tst_document_changes SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_document_changes.cpp
            ${KW_TEST_SUPPORT_DIR}/model_fixtures.h LIBS knotwork_model)
