# MPI ensembles (`mpirun -n K grainshock ensemble`). GRAINSHOCK_MPI is AUTO (on when MPI is
# found), ON (required) or OFF; AUTO looks again at every configure, so that MPI installed after
# the first configure (bootstrap.sh's `test` after its `run`) is used without clearing the cache.
# Sets GRAINSHOCK_WITH_MPI. Without MPI an ensemble is one process, on the same code path.
set(GRAINSHOCK_MPI AUTO CACHE STRING "Build MPI ensembles: AUTO (when MPI is found), ON or OFF")
set_property(CACHE GRAINSHOCK_MPI PROPERTY STRINGS AUTO ON OFF)
# A BOOL here was cached by the option() of earlier versions from the search's result of that
# configure, not chosen: it goes back to AUTO.
get_property(_gs_mpi_type CACHE GRAINSHOCK_MPI PROPERTY TYPE)
if(_gs_mpi_type STREQUAL "BOOL")
  set_property(CACHE GRAINSHOCK_MPI PROPERTY TYPE STRING)
  set_property(CACHE GRAINSHOCK_MPI PROPERTY VALUE AUTO)
endif()
string(TOUPPER "${GRAINSHOCK_MPI}" _gs_mpi)
if(NOT _gs_mpi MATCHES "^(AUTO|ON|OFF)$")
  message(FATAL_ERROR "GRAINSHOCK_MPI is '${GRAINSHOCK_MPI}': use AUTO, ON or OFF")
endif()

set(GRAINSHOCK_WITH_MPI OFF)
if(NOT _gs_mpi STREQUAL "OFF")
  set(MPI_CXX_SKIP_MPICXX TRUE)  # the C API only
  # Debian's lammps brings Open MPI's compiler wrappers without its headers (libopenmpi-dev),
  # and FindMPI then fails the whole configure on the missing include directory: MPI is looked
  # for only where its header is (Open MPI's own folder, or mpi-default-dev's and MPICH's). A
  # header not found is looked for again at the next configure (find_file keeps only hits).
  find_file(GRAINSHOCK_MPI_HEADER mpi.h
            PATHS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/openmpi/include
            PATH_SUFFIXES mpi mpich openmpi)
  if(GRAINSHOCK_MPI_HEADER)
    find_package(MPI COMPONENTS CXX)
  endif()
  if(MPI_CXX_FOUND)
    set(GRAINSHOCK_WITH_MPI ON)
  elseif(_gs_mpi STREQUAL "ON")
    message(FATAL_ERROR "GRAINSHOCK_MPI is ON but no MPI was found (Debian: libopenmpi-dev)")
  endif()
endif()
if(GRAINSHOCK_WITH_MPI)
  message(STATUS "grainshock: MPI ensembles on (GRAINSHOCK_MPI=${GRAINSHOCK_MPI})")
else()
  message(STATUS "grainshock: MPI ensembles off (GRAINSHOCK_MPI=${GRAINSHOCK_MPI}; "
                 "MPI found: ${MPI_CXX_FOUND}; Debian: libopenmpi-dev); ensembles run in one process")
endif()
