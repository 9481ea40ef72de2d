# cmake -DDIR=<folder> -P check-paper-figures.cmake: fails unless every figure of the paper's tutorials is there
# and non-empty.
foreach(f fig1-key-morph.png fig4-pliers-morph.png fig2-start.png fig2-final.png fig2-rotation.png
          fig3-translation.png fig5-interleaved.png)
  if(NOT EXISTS ${DIR}/${f})
    message(FATAL_ERROR "missing ${DIR}/${f}")
  endif()
  file(SIZE ${DIR}/${f} size)
  if(size LESS 1000)
    message(FATAL_ERROR "${DIR}/${f} is only ${size} bytes")
  endif()
  message(STATUS "${f}: ${size} bytes")
endforeach()
