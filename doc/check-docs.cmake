# The docs test: builds the site with doxygen and fails on any warning (undocumented public member, broken
# reference, unresolved \snippet), printing each one.
#   cmake -DDOXYGEN=<doxygen> -DDOXYFILE=<Doxyfile-check> -DLOG=<warnings.log> -P check-docs.cmake
file(REMOVE "${LOG}")
get_filename_component(log_dir "${LOG}" DIRECTORY)
file(MAKE_DIRECTORY "${log_dir}") # doxygen opens its warning log before it makes its output folder
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
