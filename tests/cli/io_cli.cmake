# io/config tests: cli/config.cpp is not in a library, so test_io compiles it in.
if(TARGET test_io)
  target_sources(test_io PRIVATE ${PROJECT_SOURCE_DIR}/cli/config.cpp)
endif()
