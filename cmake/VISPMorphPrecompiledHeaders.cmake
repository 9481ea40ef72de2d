# vispmorph_precompile_headers(<target> <kind>)
#
# With VISPMORPH_PRECOMPILED_HEADERS, <target> compiles against the precompiled third-party headers of its kind:
# module (the libraries), test (the Catch2 executables) or executable (apps, tools, tutorials). Every target of a
# kind reuses (REUSE_FROM) the one PCH of a host target, vispmorph_pch_<kind>, which has the kind's compile flags
# and no definitions: a PCH is used only where every definition it was built with is defined alike (gcc), and the
# targets differ in theirs (<target>_EXPORTS, the data folders), never in the flags or in what the headers test.
#
# Only stable third-party headers are listed (the suite's own change often and would rebuild everything): ViSP's core
# headers, which nearly every source includes through the suite's own, and per kind what most of its sources include.
# A list stays short: a larger PCH costs every source more to load than it saves in parsing.
set(VISPMORPH_PCH_VISP <visp3/core/vpCameraParameters.h> <visp3/core/vpHomogeneousMatrix.h> <visp3/core/vpImage.h>
                       <visp3/core/vpImagePoint.h> <visp3/core/vpMatrix.h>)
set(VISPMORPH_PCH_module ${VISPMORPH_PCH_VISP})
set(VISPMORPH_PCH_test <catch2/catch.hpp> ${VISPMORPH_PCH_VISP})
set(VISPMORPH_PCH_executable <nlohmann/json.hpp> <visp3/io/vpImageIo.h> ${VISPMORPH_PCH_VISP})

function(vispmorph_precompile_headers target kind)
  if(NOT VISPMORPH_PRECOMPILED_HEADERS)
    return()
  endif()
  set(host vispmorph_pch_${kind})
  if(NOT TARGET ${host})
    add_library(${host} OBJECT EXCLUDE_FROM_ALL ${PROJECT_SOURCE_DIR}/cmake/vispmorph_pch.cpp)
    target_include_directories(${host} SYSTEM PRIVATE ${VISP_INCLUDE_DIRS})
    if(kind STREQUAL "test")
      target_link_libraries(${host} PRIVATE Catch2::Catch2)
    else()
      target_compile_options(${host} PRIVATE -Wall -Wextra)
    endif()
    if(kind STREQUAL "module")
      set_target_properties(${host} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    endif()
    target_precompile_headers(${host} PRIVATE ${VISPMORPH_PCH_${kind}})
  endif()
  target_precompile_headers(${target} REUSE_FROM ${host})
endfunction()
