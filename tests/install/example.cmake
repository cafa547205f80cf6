# ctest InstallPackage.Example: installs the build tree into a scratch prefix, builds examples/
# against it with find_package(grainshock) and with pkg-config, and runs both programs.
# Arguments: -DBUILD_DIR= -DSOURCE_DIR= -DWORK= [-DLAUNCHER=ccache] [-DCXX=compiler]
file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f bin/grainshock include/grainshock/sim/engine.h include/grainshock/render/renderer.h
          lib/cmake/grainshock/grainshockConfig.cmake lib/pkgconfig/grainshock.pc)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "cmake --install did not install ${f}")
  endif()
endforeach()

# CMake package, with the build tree out of sight: only the prefix is searched.
set(launcher "")
if(LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples -B ${WORK}/build -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX} ${launcher})
run(${CMAKE_COMMAND} --build ${WORK}/build)
run(${WORK}/build/kick_and_render ${WORK}/cmake.png)
message(STATUS "${last_output}")

# pkg-config: one compiler line.
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
run(pkg-config --cflags --libs grainshock)
string(STRIP "${last_output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${LAUNCHER} ${CXX} -O2 ${SOURCE_DIR}/examples/kick_and_render.cpp ${flags}
    -o ${WORK}/kick_and_render_pc)
run(${WORK}/kick_and_render_pc ${WORK}/pkgconfig.png)

# The same deterministic run gives the same picture both ways; the installed program says so.
run(${prefix}/bin/grainshock compare ${WORK}/cmake.png ${WORK}/pkgconfig.png)
message(STATUS "${last_output}")
