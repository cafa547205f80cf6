# Per-target settings shared by every grainshock target (no global flags).

# The engine runs faster with AVX2 (x86-64-v3: packing 0.5 +7%, kicks 3% less run time), so the
# program is built for it when the build machine has it. All of it, not only the engine: Eigen
# sizes its alignment to the widest vectors a file is compiled for, and objects handed between
# files compiled differently would be freed wrongly. FMA stays off: it rounds a * b + c once
# instead of twice, and histories would then depend on the machine; without it they are
# byte-identical to a baseline x86-64 build. Turn the option off for older x86-64 machines.
option(GRAINSHOCK_AVX2 "Build for x86-64-v3 (without FMA) when the build machine supports it" ON)
if(GRAINSHOCK_AVX2)
  include(CheckCXXSourceRuns)
  check_cxx_source_runs("int main() { return __builtin_cpu_supports(\"x86-64-v3\") ? 0 : 1; }"
                        GRAINSHOCK_HOST_HAS_X86_64_V3)
endif()

# ASan + UBSan for the whole suite (README, "Sanitizers"). Options are PUBLIC so that whatever
# links a sanitized library, the installed example included, is linked with the runtimes too.
option(GRAINSHOCK_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)

function(grainshock_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  # PUBLIC: code that includes the headers must agree on Eigen's alignment (see above).
  if(GRAINSHOCK_AVX2 AND GRAINSHOCK_HOST_HAS_X86_64_V3)
    target_compile_options(${target} PUBLIC -march=x86-64-v3 -mno-fma)
  endif()
  if(GRAINSHOCK_SANITIZE)
    # -fno-sanitize-recover: a UBSan finding fails the test instead of scrolling past.
    set(san -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
    target_compile_options(${target} PUBLIC ${san})
    target_link_options(${target} PUBLIC ${san})
  endif()
endfunction()

# Compiles files in as strings at build time: adds to `target` a generated source defining
# `std::string_view NAME()` in `namespace` for each NAME=PATH given (cmake/EmbedFiles.cmake), so
# that assets stay files of their own and the program needs none at run time.
function(grainshock_embed_files target namespace)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/${target}_embedded.cpp)
  set(paths)
  foreach(entry IN LISTS ARGN)
    string(REGEX REPLACE "^[^=]*=" "" path "${entry}")
    list(APPEND paths ${path})
  endforeach()
  list(JOIN ARGN "," files)
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DNAMESPACE=${namespace} "-DFILES=${files}" -DOUT=${out}
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake
    DEPENDS ${paths} ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake
    COMMENT "Embedding ${namespace}")
  target_sources(${target} PRIVATE ${out})
endfunction()
