# Installing (label app): the relocatable install tree, the manual page against --help, and the
# Debian package (also labelled package; it runs where CI runs, as root, and skips elsewhere).
#   xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build -L package --output-on-failure
add_test(NAME app_install COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/install_tree.sh
         ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${PROJECT_VERSION})
set_tests_properties(app_install PROPERTIES LABELS "app;gl" TIMEOUT 600)

add_test(NAME app_manpage COMMAND ${CMAKE_COMMAND} -DKNOTWORK=$<TARGET_FILE:knotwork>
         -DMANPAGE=${PROJECT_BINARY_DIR}/packaging/knotwork.1
         -P ${PROJECT_SOURCE_DIR}/tools/check_manpage.cmake)
set_tests_properties(app_manpage PROPERTIES LABELS app)

add_test(NAME app_package COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/package_deb.sh
         ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR} ${PROJECT_VERSION})
# RUN_SERIAL: apt holds the dpkg lock, and the installed /usr/bin/knotwork should not be seen by
# tests running beside it.
set_tests_properties(app_package PROPERTIES LABELS "app;package" TIMEOUT 900 SKIP_RETURN_CODE 77
                     RUN_SERIAL TRUE)

# File > Open Sample finds the samples in the data folder, as the installed editor does.
kw_add_test(tst_samples_menu LABEL gui SOURCES ${CMAKE_CURRENT_LIST_DIR}/tst_samples_menu.cpp
            ${CMAKE_CURRENT_LIST_DIR}/editor_test_util.h LIBS knotwork_ui)
