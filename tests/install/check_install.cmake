# The "install" test: install the suite's build tree into a fresh prefix, then configure, build and run an
# unrelated project (this folder) that knows nothing but find_package(VISPMorph) and that prefix.
#
#   cmake -DBUILD_DIR=<suite build> -DWORK_DIR=<scratch> -DSOURCE_DIR=<suite source> [-DGENERATOR=...]
#         [-DCXX_COMPILER=...] [-DCXX_FLAGS=...] [-DBUILD_TYPE=...] -P check_install.cmake
#
# Everything happens under WORK_DIR, which is wiped first, so the test depends on no other test.
foreach(v BUILD_DIR WORK_DIR SOURCE_DIR)
  if(NOT ${v})
    message(FATAL_ERROR "check_install.cmake: ${v} is not set")
  endif()
endforeach()
if(NOT BUILD_TYPE)
  set(BUILD_TYPE Release)
endif()

set(prefix "${WORK_DIR}/prefix")
set(app_build "${WORK_DIR}/app-build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(run step)
  message(STATUS "[install test] ${step}: ${ARGN}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "[install test] ${step} failed (${rc})")
  endif()
endfunction()

# 1. Install into the fresh prefix.
run("install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}" --config "${BUILD_TYPE}")

# 2. The install tree holds headers, libraries and the CMake package, and no path back to the source or build tree.
file(GLOB libs "${prefix}/lib*/libvispmorph_morph.*" "${prefix}/lib*/*/libvispmorph_morph.*")
file(GLOB configs "${prefix}/lib*/cmake/VISPMorph/VISPMorphConfig.cmake" "${prefix}/lib*/*/cmake/VISPMorph/VISPMorphConfig.cmake")
if(NOT EXISTS "${prefix}/include/visp3/morph/vpMorphContour.h")
  message(FATAL_ERROR "[install test] no include/visp3/morph/vpMorphContour.h under ${prefix}")
endif()
if(NOT libs)
  message(FATAL_ERROR "[install test] no libvispmorph_morph under ${prefix}/lib")
endif()
if(NOT configs)
  message(FATAL_ERROR "[install test] no lib/cmake/VISPMorph/VISPMorphConfig.cmake under ${prefix}")
endif()
list(GET configs 0 config)
get_filename_component(package_dir "${config}" DIRECTORY)
foreach(f VISPMorphConfigVersion.cmake VISPMorphTargets.cmake)
  if(NOT EXISTS "${package_dir}/${f}")
    message(FATAL_ERROR "[install test] ${package_dir}/${f} is missing")
  endif()
endforeach()
file(GLOB package_files "${package_dir}/*.cmake")
foreach(f ${package_files})
  file(READ "${f}" text)
  foreach(tree "${SOURCE_DIR}" "${BUILD_DIR}")
    string(FIND "${text}" "${tree}/" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "[install test] ${f} refers to ${tree}: the package is not relocatable")
    endif()
  endforeach()
endforeach()
file(GLOB_RECURSE stray RELATIVE "${prefix}/include" "${prefix}/include/*")
list(FILTER stray EXCLUDE REGEX "\\.h$")
if(stray)
  message(FATAL_ERROR "[install test] non-header files installed under include/: ${stray}")
endif()

# 3. Configure, build and run the outside project against that prefix only.
set(configure_args -S "${CMAKE_CURRENT_LIST_DIR}" -B "${app_build}" "-DCMAKE_PREFIX_PATH=${prefix}"
                   "-DEXPECTED_PREFIX=${prefix}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
                   -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON)
if(GENERATOR)
  list(APPEND configure_args -G "${GENERATOR}")
endif()
if(CXX_FLAGS) # e.g. the sanitizers of a VISPMORPH_SANITIZE build: its libraries need them in the executable too
  list(APPEND configure_args "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${CXX_FLAGS}")
endif()
if(CXX_COMPILER)
  list(APPEND configure_args "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif()
run("configure outside project" "${CMAKE_COMMAND}" ${configure_args})
run("build outside project" "${CMAKE_COMMAND}" --build "${app_build}" --config "${BUILD_TYPE}")
foreach(exe app app_vars)
  set(path "${app_build}/${exe}")
  if(NOT EXISTS "${path}")
    set(path "${app_build}/${BUILD_TYPE}/${exe}")
  endif()
  run("run ${exe}" "${path}")
endforeach()
message(STATUS "[install test] passed: ${prefix}")
