# Warnings for our own code only: GCC 12 -O3 reports false -Warray-bounds inside Eigen/PCL, so no -Werror.
function(twinslam_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-array-bounds)
endfunction()

# twinslam_library(NAME SOURCES... [PUBLIC_LINKS ...] [PRIVATE_LINKS ...])
# A library whose public headers live in <dir>/include. All project libraries are static: one self-contained
# binary per service is simpler to ship into a container or onto a drone.
function(twinslam_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_LINKS;PRIVATE_LINKS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_LINKS} PRIVATE ${ARG_PRIVATE_LINKS})
  twinslam_warnings(${name})
endfunction()

# twinslam_test(NAME SOURCES... LINKS ... [LABELS ...] [TIMEOUT s] [SERIAL])
# A GoogleTest executable registered as one ctest test per TEST() (gtest_discover_tests).
# TWINSLAM_SHARED_DIR and the bin folder are passed as compile definitions so tests find data and binaries.
function(twinslam_test name)
  cmake_parse_arguments(ARG "SERIAL" "TIMEOUT" "SOURCES;LINKS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LINKS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    TWINSLAM_SHARED_DIR="${TWINSLAM_SHARED_DIR}"
    TWINSLAM_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    TWINSLAM_BIN_DIR="${CMAKE_RUNTIME_OUTPUT_DIRECTORY}")
  twinslam_warnings(${name})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 120)
  endif()
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  set(serial FALSE)
  if(ARG_SERIAL)
    set(serial TRUE)  # e.g. tests that inspect machine-wide state such as /dev/shm
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60
    PROPERTIES TIMEOUT ${ARG_TIMEOUT} LABELS "${ARG_LABELS}" RUN_SERIAL ${serial})
endfunction()

# Adds every immediate subfolder that has a CMakeLists.txt, so new modules need no edit of the parent.
function(twinslam_add_subdirectories)
  file(GLOB children LIST_DIRECTORIES true RELATIVE ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/*)
  list(SORT children)
  foreach(child ${children})
    if(IS_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/${child} AND EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${child}/CMakeLists.txt)
      add_subdirectory(${child})
    endif()
  endforeach()
endfunction()

# twinslam_service(NAME NODE_SOURCES ... [LINKS ...]): a service's DDS node library twinslam_<NAME>_node (the
# node sources, linkable into tests so two services can share a process) and its executable twinslam-<NAME> (main.cpp).
function(twinslam_service name)
  cmake_parse_arguments(ARG "" "" "NODE_SOURCES;LINKS" ${ARGN})
  add_library(twinslam_${name}_node STATIC ${ARG_NODE_SOURCES})
  target_include_directories(twinslam_${name}_node PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(twinslam_${name}_node PUBLIC twinslam_dds ${ARG_LINKS})
  twinslam_warnings(twinslam_${name}_node)
  add_executable(twinslam_${name} main.cpp)
  set_target_properties(twinslam_${name} PROPERTIES OUTPUT_NAME twinslam-${name})
  target_link_libraries(twinslam_${name} PRIVATE twinslam_${name}_node)
  twinslam_warnings(twinslam_${name})
endfunction()
