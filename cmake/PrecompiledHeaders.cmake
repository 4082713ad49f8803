# Precompiled headers: the standard, Eigen and OpenCV headers that most files include (and
# GoogleTest for the tests) are parsed once per build instead of once per file. Why: CI
# builds everything twice (Release, then the sanitizers) on 2 cores, and parsing these
# headers is 1-2.5 s of each file's 2-40 s with g++ -O3 and 1-6 s with clang -O1 under the
# sanitizers (measured on heap_test, likelihood_test and trainer_test).
#
# Two owners compile them, one per kind of target, so that each PCH is built with the
# flags of the targets that reuse it (a clang PCH is refused when -fPIC/-fPIE or a macro
# it saw differ): jgpm_pch_library for the static libraries, jgpm_pch_test (an executable
# linked like a test) for the tests. Other targets (the `jgpm` executable, the Python
# module, benchmarks, fuzzers) compile as before. -DJGPM_PCH=OFF turns it off, which also
# shows a file that forgot one of these includes.
#
#   jgpm_precompile_headers()  after every add_subdirectory
set(JGPM_PCH_HEADERS <algorithm> <cmath> <cstdint> <filesystem> <functional> <map> <memory>
    <random> <string> <vector> <Eigen/Core> <Eigen/Geometry> <opencv2/core.hpp>)

function(jgpm_collect_targets dir out)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(children DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(child IN LISTS children)
    jgpm_collect_targets(${child} child_targets)
    list(APPEND targets ${child_targets})
  endforeach()
  set(${out} ${targets} PARENT_SCOPE)
endfunction()

function(jgpm_precompile_headers)
  if(NOT JGPM_PCH)
    return()
  endif()
  jgpm_collect_targets(${PROJECT_SOURCE_DIR} targets)

  add_library(jgpm_pch_library STATIC ${PROJECT_SOURCE_DIR}/cmake/pch.cc)
  target_link_libraries(jgpm_pch_library PRIVATE Eigen3::Eigen opencv_core)
  target_precompile_headers(jgpm_pch_library PRIVATE ${JGPM_PCH_HEADERS})
  if(TARGET jgpm_test_support)
    add_executable(jgpm_pch_test ${PROJECT_SOURCE_DIR}/cmake/pch.cc)
    target_link_libraries(jgpm_pch_test PRIVATE jgpm_test_support GTest::gtest_main Eigen3::Eigen opencv_core)
    target_precompile_headers(jgpm_pch_test PRIVATE ${JGPM_PCH_HEADERS} <gtest/gtest.h>)
  endif()

  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    get_target_property(links ${target} LINK_LIBRARIES)
    if(type STREQUAL "STATIC_LIBRARY" AND target MATCHES "^jgpm_(io|prior|calibration|tracker)")
      set(owner jgpm_pch_library)
    elseif(type STREQUAL "EXECUTABLE" AND target MATCHES "_test$" AND "jgpm_test_support" IN_LIST links)
      set(owner jgpm_pch_test)
    else()
      continue()
    endif()
    # The headers' folders, in case a compiler refuses the PCH and parses them after all.
    target_include_directories(${target} SYSTEM PRIVATE
      $<TARGET_PROPERTY:Eigen3::Eigen,INTERFACE_INCLUDE_DIRECTORIES> ${OpenCV_INCLUDE_DIRS})
    target_precompile_headers(${target} REUSE_FROM ${owner})
  endforeach()
endfunction()
