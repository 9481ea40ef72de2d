# The docs test: builds the site with doxygen and fails on any warning (undocumented public member, broken
# reference, unresolved \snippet), printing each one.
#   cmake -DDOXYGEN=<doxygen> -DDOXYFILE=<Doxyfile-check> -DLOG=<warnings.log>
#         [-DVISP_TAG=<ViSP's tag file> -DVISP_TAG_DOXYFILE=<its Doxyfile>] -P check-docs.cmake
# ViSP's tag file is made first when it is missing (a few seconds, once).
file(REMOVE "${LOG}")
get_filename_component(log_dir "${LOG}" DIRECTORY)
file(MAKE_DIRECTORY "${log_dir}") # doxygen opens its warning log before it makes its output folder
if(VISP_TAG AND NOT EXISTS "${VISP_TAG}")
  execute_process(COMMAND "${DOXYGEN}" "${VISP_TAG_DOXYFILE}" RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR NOT EXISTS "${VISP_TAG}")
    message(FATAL_ERROR "doxygen could not make ViSP's tag file ${VISP_TAG} (exit code ${rc})")
  endif()
endif()
execute_process(COMMAND "${DOXYGEN}" "${DOXYFILE}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "doxygen failed (exit code ${rc})")
endif()
file(STRINGS "${LOG}" lines REGEX "warning:")
list(LENGTH lines errors)
foreach(l IN LISTS lines)
  message("${l}")
endforeach()
if(errors GREATER 0)
  message(FATAL_ERROR "${errors} doxygen warnings")
endif()
message("docs: site built with no warning")
