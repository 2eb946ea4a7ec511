# hba_add_module(<name> SOURCES ... DEPS ... PRIVATE_DEPS ...)
# Defines the static library hba_<name> (alias hba::<name>) of one module;
# a module without sources yet is an interface library.
function(hba_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  set(target hba_${name})
  if(ARG_SOURCES)
    add_library(${target} STATIC ${ARG_SOURCES})
    target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated>
                                                $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    # src/ holds the internal headers modules share ("io/cloud_store.hpp"):
    # they are not installed.
    target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(${target} PUBLIC ${ARG_DEPS} PRIVATE $<BUILD_INTERFACE:hba_warnings> ${ARG_PRIVATE_DEPS})
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                   $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  # Installed as hba::<name> (hba_core -> hba::core).
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  add_library(hba::${name} ALIAS ${target})
  set_property(GLOBAL APPEND PROPERTY HBA_MODULE_TARGETS ${target})
endfunction()

# hba_add_test(<name> SOURCES ... DEPS ...)
# A GoogleTest executable whose tests ctest discovers one by one.
function(hba_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} hba_test_support GTest::gtest GTest::gtest_main
                                        hba_warnings)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${HBA_TEST_TIMEOUT})
endfunction()

# hba_add_benchmark(<name> SOURCES ... DEPS ...)
function(hba_add_benchmark name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} benchmark::benchmark hba_warnings)
endfunction()
