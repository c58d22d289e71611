# legwork_module(NAME [DIR d] DEPS a b ... LIBS x y ...)
# One static library per module: sources are src/NAME/*.cpp (or src/DIR/*.cpp),
# public headers include/legwork/NAME/*.hpp. Exposed as legwork::NAME.
# Runtime modules (per-frame code) are NAME; their offline tools (builders,
# file formats, whole-clip helpers) are NAME_offline with DIR NAME/offline,
# headers in include/legwork/NAME/offline/.
function(legwork_module name)
  cmake_parse_arguments(ARG "" "DIR" "DEPS;LIBS" ${ARGN})
  if(NOT ARG_DIR)
    set(ARG_DIR ${name})
  endif()
  file(GLOB srcs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${ARG_DIR}/*.cpp)
  if(NOT srcs)
    message(STATUS "legwork: module ${name} has no sources yet; skipped")
    return()
  endif()
  add_library(legwork_${name} STATIC ${srcs})
  add_library(legwork::${name} ALIAS legwork_${name})
  target_include_directories(legwork_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
  target_compile_features(legwork_${name} PUBLIC cxx_std_20)
  foreach(d IN LISTS ARG_DEPS)
    target_link_libraries(legwork_${name} PUBLIC legwork::${d})
  endforeach()
  target_link_libraries(legwork_${name} PUBLIC ${ARG_LIBS})
  set_target_properties(legwork_${name} PROPERTIES EXPORT_NAME ${name})
  legwork_warnings(legwork_${name})
  if(LEGWORK_MODULE_OPT)
    target_compile_options(legwork_${name} PRIVATE ${LEGWORK_MODULE_OPT})
  endif()
  install(TARGETS legwork_${name} EXPORT legworkTargets ARCHIVE DESTINATION lib)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/legwork/${name} DESTINATION include/legwork OPTIONAL)
endfunction()

function(legwork_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wno-psabi
    # GCC 12 false positives in std::string concatenation (GCC bug 105329).
    $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
  if(LEGWORK_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# legwork_tests(NAME LIBS ... [SUITES_IN_ONE_PROCESS Suite ...]):
# tests/NAME/*_test.cpp -> one gtest executable, each test a ctest entry of
# its own, except the suites named after SUITES_IN_ONE_PROCESS: each of those
# is one entry (`Suite.*`) that runs all its tests in one process, for suites
# whose tests share an expensive static fixture (an evaluation run, a
# database) that a process per test would build again for every test (under
# the sanitizers, 20 s each).
function(legwork_tests name)
  cmake_parse_arguments(ARG "" "" "LIBS;SUITES_IN_ONE_PROCESS" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tests/${name}/*_test.cpp)
  if(NOT srcs)
    return()
  endif()
  add_executable(test_${name} ${srcs})
  target_link_libraries(test_${name} PRIVATE ${ARG_LIBS} legwork_testdata GTest::gtest_main)
  legwork_warnings(test_${name})
  set(filter "")
  foreach(suite IN LISTS ARG_SUITES_IN_ONE_PROCESS)
    string(APPEND filter "${suite}.*:")
    add_test(NAME ${suite}.* COMMAND test_${name} --gtest_filter=${suite}.*)
    set_tests_properties(${suite}.* PROPERTIES ENVIRONMENT "LEGWORK_SOURCE_DIR=${PROJECT_SOURCE_DIR}" LABELS test_${name})
  endforeach()
  if(filter)
    set(filter TEST_FILTER "-${filter}")
  endif()
  gtest_discover_tests(test_${name} DISCOVERY_TIMEOUT 60 ${filter}
    PROPERTIES ENVIRONMENT "LEGWORK_SOURCE_DIR=${PROJECT_SOURCE_DIR}" LABELS test_${name})
endfunction()

# legwork_link_modules(TARGET): links every module library that exists (the
# runtime and offline target of each module) into TARGET, privately. For the
# CLI, benchmarks and checks that use everything.
function(legwork_link_modules target)
  foreach(m IN LISTS LEGWORK_MODULES)
    foreach(t ${m} ${m}_offline)
      if(TARGET legwork_${t})
        target_link_libraries(${target} PRIVATE legwork::${t})
      endif()
    endforeach()
  endforeach()
endfunction()
