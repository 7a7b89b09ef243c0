# Installing (label app): the relocatable install tree and the manual page against --help.
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -R '^app_' --output-on-failure
add_test(NAME app_install COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/install_tree.sh
         ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${PROJECT_VERSION})
set_tests_properties(app_install PROPERTIES LABELS "app;gl" TIMEOUT 600)

add_test(NAME app_manpage COMMAND ${CMAKE_COMMAND} -DKNOTWORK=$<TARGET_FILE:knotwork>
         -DMANPAGE=${PROJECT_BINARY_DIR}/packaging/knotwork.1
         -P ${PROJECT_SOURCE_DIR}/tools/check_manpage.cmake)
set_tests_properties(app_manpage PROPERTIES LABELS app)
