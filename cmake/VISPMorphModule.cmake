# vispmorph_add_module(<name> DEPS <vispmorph modules> VISP <visp targets> PRIVATE_LIBS <libs> [LOOP_TESTS])
#
# Builds modules/<name> as the library vispmorph_<name> (exported as VISPMorph::<name>), ViSP style:
# public headers in include/visp3/<name>/, sources in src/, unit tests in test/ (one Catch2 executable).
# LOOP_TESTS: the module's Catch2 tests tagged [loop] (closed-loop runs of a simulated robot on rendered images, each
# several seconds) get the ctest label `long`, which `./vispmorph test` leaves to `./vispmorph test-long`.
function(vispmorph_add_module name)
  cmake_parse_arguments(M "LOOP_TESTS" "" "DEPS;VISP;PRIVATE_LIBS" ${ARGN})
  file(GLOB_RECURSE srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  file(GLOB_RECURSE hdrs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/include/visp3/${name}/*.h)
  set(target vispmorph_${name})
  add_library(${target} ${srcs} ${hdrs})
  add_library(VISPMorph::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME vispmorph_${name}
                                             VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}
                                             POSITION_INDEPENDENT_CODE ON)
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                              $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  # ViSP targets are not namespaced and carry no include directories of their own.
  target_include_directories(${target} SYSTEM PUBLIC "$<BUILD_INTERFACE:${VISP_INCLUDE_DIRS}>")
  set(deps)
  foreach(d ${M_DEPS})
    list(APPEND deps vispmorph_${d})
  endforeach()
  target_link_libraries(${target} PUBLIC ${deps} ${M_VISP} PRIVATE ${M_PRIVATE_LIBS})
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  vispmorph_precompile_headers(${target} module)
  install(TARGETS ${target} EXPORT VISPMorphTargets
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  # Headers only: editor backups and temporary files next to them are not part of the package.
  install(DIRECTORY include/visp3 DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
  set_property(GLOBAL APPEND PROPERTY VISPMORPH_MODULES ${name})

  file(GLOB tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/test/*.cpp)
  if(VISPMORPH_BUILD_TESTS AND tests)
    add_executable(test_${name} ${tests})
    target_link_libraries(test_${name} PRIVATE ${target} vispmorph_catch_main)
    vispmorph_precompile_headers(test_${name} test)
    target_compile_definitions(test_${name} PRIVATE VISPMORPH_DATA_DIR="${VISPMORPH_DATA_DIR}"
                                                    VISPMORPH_DATASETS_DIR="${VISPMORPH_DATASETS_DIR}")
    # The test cases tagged [datasets] read the shape datasets in place: one ctest runs them all, reported as
    # skipped (exit code 77) where VISPMORPH_DATASETS_DIR does not exist.
    if(M_LOOP_TESTS)
      catch_discover_tests(test_${name} TEST_PREFIX "${name}: " TEST_SPEC "~[loop]~[datasets]"
                           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
      catch_discover_tests(test_${name} TEST_PREFIX "${name}: " TEST_SPEC "[loop]~[datasets]"
                           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR} PROPERTIES LABELS long)
    else()
      catch_discover_tests(test_${name} TEST_PREFIX "${name}: " TEST_SPEC "~[datasets]"
                           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
    endif()
    set(dataset_tests)
    foreach(t ${tests})
      file(STRINGS ${t} tagged REGEX "\\[datasets\\]")
      list(APPEND dataset_tests ${tagged})
    endforeach()
    if(dataset_tests)
      add_test(NAME "${name}: tests on the shape datasets"
               COMMAND sh -c "test -d '${VISPMORPH_DATASETS_DIR}' || { echo 'SKIPPED: no shape datasets in ${VISPMORPH_DATASETS_DIR} (-DVISPMORPH_DATASETS_DIR=DIR)'; exit 77; }; exec \"$<TARGET_FILE:test_${name}>\" '[datasets]'"
               WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
      set_tests_properties("${name}: tests on the shape datasets" PROPERTIES SKIP_RETURN_CODE 77 LABELS datasets)
    endif()
  endif()
endfunction()

# vispmorph_add_executable(<target> <sources> LIBS <libs>): an app, tutorial or tool linked to the modules.
function(vispmorph_add_executable target)
  cmake_parse_arguments(E "" "" "LIBS" ${ARGN})
  add_executable(${target} ${E_UNPARSED_ARGUMENTS})
  target_link_libraries(${target} PRIVATE ${E_LIBS})
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  vispmorph_precompile_headers(${target} executable)
  target_compile_definitions(${target} PRIVATE VISPMORPH_DATA_DIR="${VISPMORPH_DATA_DIR}"
                                               VISPMORPH_DATASETS_DIR="${VISPMORPH_DATASETS_DIR}")
endfunction()
