# ctest Configure.MpiFoundWhenInstalledLater: bootstrap.sh configures once before MPI is
# installed (`run`) and again after (`test`); the second configure must build MPI ensembles.
# MPI's absence at the first configure is played by CMAKE_DISABLE_FIND_PACKAGE_MPI.
# Arguments: -DSOURCE_DIR= -DWORK= [-DCXX=compiler]
file(REMOVE_RECURSE ${WORK})

function(configure)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK} -DCMAKE_BUILD_TYPE=Release
                          -DCMAKE_CXX_COMPILER=${CXX} ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configure failed (${rc}): ${ARGN}\n${out}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
  # Whether the ensembles are built on MPI: the rank code the build compiles.
  file(GLOB_RECURSE made ${WORK}/analysis/CMakeFiles/grainshock_ensemble.dir/build.make)
  file(READ ${made} rules)
  if(rules MATCHES "ensemble_ranks_mpi")
    set(with_mpi ON PARENT_SCOPE)
  else()
    set(with_mpi OFF PARENT_SCOPE)
  endif()
endfunction()

configure(-DCMAKE_DISABLE_FIND_PACKAGE_MPI=ON)
if(with_mpi)
  message(FATAL_ERROR "MPI ensembles on while MPI was hidden:\n${last_output}")
endif()
configure(-DCMAKE_DISABLE_FIND_PACKAGE_MPI=OFF)
if(NOT with_mpi)
  message(FATAL_ERROR "MPI present at the second configure but ensembles built without it:\n"
                      "${last_output}")
endif()
# An explicit OFF is kept.
configure(-DGRAINSHOCK_MPI=OFF)
if(with_mpi)
  message(FATAL_ERROR "-DGRAINSHOCK_MPI=OFF not honoured:\n${last_output}")
endif()
file(REMOVE_RECURSE ${WORK})
