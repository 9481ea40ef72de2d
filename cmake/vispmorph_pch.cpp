// The translation unit that builds a kind's precompiled headers (cmake/VISPMorphPrecompiledHeaders.cmake): empty.
