# Linker (issue 25): ~100 executables (75 tests, the studio, the CLI, benchmarks) each link the
# static libraries with debug info: 3-11 s each with GNU ld, 8.7 of the 73 CPU-minutes of a cold
# default build on two cores (docs/platform.md, "Timings"). mold (Debian package `mold`,
# installed by scripts/install-deps.sh) links the same in a fraction of that.
# -DFOVEA_LINKER=bfd (or gold) chooses another; auto uses mold when it is installed.
set(FOVEA_LINKER "auto" CACHE STRING "Linker: auto (mold when installed), mold, gold, bfd")
if(FOVEA_LINKER STREQUAL "auto")
  find_program(FOVEA_MOLD mold)
  if(FOVEA_MOLD)
    set(_fovea_linker mold)
  endif()
elseif(NOT FOVEA_LINKER STREQUAL "bfd")
  set(_fovea_linker ${FOVEA_LINKER})
endif()
if(_fovea_linker)
  add_link_options(-fuse-ld=${_fovea_linker})
  message(STATUS "fovea: linking with ${_fovea_linker}")
endif()
