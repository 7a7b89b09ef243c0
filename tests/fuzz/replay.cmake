# Fuzz regression tests: every harness in tests/fuzz/ replays its seed corpus and every
# reproducer ever found (tests/fuzz/corpus/NAME, tests/fuzz/repro/NAME) through the normal
# build, without libFuzzer. The fuzzing itself runs in the clang build: tools/dev.sh fuzz.
set(KW_FUZZ_DIR ${CMAKE_CURRENT_LIST_DIR})
foreach(harness knot obj trim document)
  add_executable(fuzz_replay_${harness} ${KW_FUZZ_DIR}/fuzz_${harness}.cpp
                 ${KW_FUZZ_DIR}/replay_main.cpp ${KW_FUZZ_DIR}/fuzz_util.h
                 ${KW_FUZZ_DIR}/fuzz_roundtrip.h)
  target_link_libraries(fuzz_replay_${harness} PRIVATE knotwork_model)
  set(inputs ${KW_FUZZ_DIR}/corpus/${harness})
  if(EXISTS ${KW_FUZZ_DIR}/repro/${harness})
    list(APPEND inputs ${KW_FUZZ_DIR}/repro/${harness})
  endif()
  add_test(NAME fuzz_replay_${harness} COMMAND fuzz_replay_${harness} ${inputs})
  set_tests_properties(fuzz_replay_${harness} PROPERTIES LABELS "model;fuzz"
    ENVIRONMENT "QT_QPA_PLATFORM=offscreen")
endforeach()
# The CAD reader child's checks before OpenCASCADE (model/cad/cadprecheck.h), on STEP and IGES.
foreach(harness step iges)
  add_executable(fuzz_replay_${harness} ${KW_FUZZ_DIR}/fuzz_${harness}.cpp
                 ${KW_FUZZ_DIR}/replay_main.cpp ${KW_FUZZ_DIR}/fuzz_util.h ${KW_FUZZ_DIR}/fuzz_cad.h)
  target_link_libraries(fuzz_replay_${harness} PRIVATE knotwork_cad)
  set(inputs ${KW_FUZZ_DIR}/corpus/${harness})
  if(EXISTS ${KW_FUZZ_DIR}/repro/${harness})
    list(APPEND inputs ${KW_FUZZ_DIR}/repro/${harness})
  endif()
  add_test(NAME fuzz_replay_${harness} COMMAND fuzz_replay_${harness} ${inputs})
  set_tests_properties(fuzz_replay_${harness} PROPERTIES LABELS "model;fuzz"
    ENVIRONMENT "QT_QPA_PLATFORM=offscreen")
endforeach()
