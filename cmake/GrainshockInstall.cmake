# `cmake --install`: the grainshock program, the libraries with their headers, a CMake package
# (find_package(grainshock): grainshock::sim, grainshock::io, grainshock::analysis,
# grainshock::render, grainshock::movie) and a pkg-config file. The package is relocatable: it finds itself and its
# headers relative to where it was installed.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(GRAINSHOCK_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/grainshock)
set(GRAINSHOCK_INCLUDE_DIR ${CMAKE_INSTALL_INCLUDEDIR}/grainshock)
set(_libs grainshock_sim grainshock_io grainshock_analysis grainshock_render grainshock_movie)
foreach(lib ${_libs})
  string(REPLACE "grainshock_" "" short ${lib})
  set_target_properties(${lib} PROPERTIES EXPORT_NAME ${short})
  target_include_directories(${lib} INTERFACE $<INSTALL_INTERFACE:${GRAINSHOCK_INCLUDE_DIR}>)
endforeach()

install(TARGETS grainshock RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS ${_libs} EXPORT grainshockTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
# Headers keep their folders, as the sources include them: #include "sim/engine.h".
install(DIRECTORY sim io analysis render DESTINATION ${GRAINSHOCK_INCLUDE_DIR}
        FILES_MATCHING PATTERN "*.h")
install(EXPORT grainshockTargets NAMESPACE grainshock:: DESTINATION ${GRAINSHOCK_CMAKE_DIR})

# The static libraries' private dependencies must be found again by whoever links them.
if(TARGET PkgConfig::EGL)
  set(GRAINSHOCK_WITH_EGL ON)
  set(GRAINSHOCK_PC_EGL " egl")
else()
  set(GRAINSHOCK_WITH_EGL OFF)
  set(GRAINSHOCK_PC_EGL "")
endif()
configure_package_config_file(cmake/grainshockConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/grainshockConfig.cmake INSTALL_DESTINATION ${GRAINSHOCK_CMAKE_DIR}
  PATH_VARS CMAKE_INSTALL_BINDIR)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/grainshockConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/grainshockConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/grainshockConfigVersion.cmake
        DESTINATION ${GRAINSHOCK_CMAKE_DIR})

# pkg-config: the compile options every user of the headers needs (C++20, and the instruction set
# the libraries were built for: Eigen's alignment depends on it).
get_target_property(_opts grainshock_sim INTERFACE_COMPILE_OPTIONS)
set(GRAINSHOCK_PC_CFLAGS "-std=c++20")
if(_opts)
  list(JOIN _opts " " _joined)
  string(APPEND GRAINSHOCK_PC_CFLAGS " ${_joined}")
endif()
get_target_property(_link grainshock_sim INTERFACE_LINK_OPTIONS)
set(GRAINSHOCK_PC_LIBS
    "-lgrainshock_render -lgrainshock_movie -lgrainshock_analysis -lgrainshock_io -lgrainshock_sim
     -pthread")
if(_link)
  list(JOIN _link " " _joined)
  string(APPEND GRAINSHOCK_PC_LIBS " ${_joined}")
endif()
file(RELATIVE_PATH GRAINSHOCK_PC_PREFIX /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)
string(REGEX REPLACE "/$" "" GRAINSHOCK_PC_PREFIX "${GRAINSHOCK_PC_PREFIX}")
configure_file(cmake/grainshock.pc.in ${CMAKE_CURRENT_BINARY_DIR}/grainshock.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/grainshock.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
