# libFuzzer targets (clang only): -DTESSERA_BUILD_FUZZERS=ON with
# -DCMAKE_CXX_COMPILER=clang++. Every target is built with coverage
# instrumentation and AddressSanitizer + UndefinedBehaviorSanitizer
# (-fsanitize=fuzzer-no-link,...) so the fuzzers see inside the whole
# pipeline; only the fuzzer executables link libFuzzer's main.
# tools/ci/fuzz.sh builds them in build-fuzz/ and runs each for a bounded time.
option(TESSERA_BUILD_FUZZERS "Build the libFuzzer targets in tests/fuzz (needs clang)" OFF)

if(TESSERA_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "TESSERA_BUILD_FUZZERS needs clang: configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  set(TESSERA_FUZZ_SANITIZERS "address,undefined" CACHE STRING "Sanitizers linked into the fuzzers")
  add_compile_options(-fsanitize=fuzzer-no-link,${TESSERA_FUZZ_SANITIZERS} -fno-omit-frame-pointer -g
                      -fno-sanitize-recover=undefined
                      # SimdTargets.cmake passes a g++-only warning flag.
                      -Wno-unknown-warning-option)
  add_link_options(-fsanitize=${TESSERA_FUZZ_SANITIZERS})
endif()

# Called from the top-level CMakeLists.txt once the libraries exist.
function(tessera_add_fuzzers)
  if(NOT TESSERA_BUILD_FUZZERS)
    return()
  endif()
  foreach(target scene_parser gltf_loader rasterizer)
    add_executable(fuzz_${target}
      ${PROJECT_SOURCE_DIR}/tests/fuzz/fuzz_${target}.cpp
      ${PROJECT_SOURCE_DIR}/tests/fuzz/fuzz_targets.cpp)
    target_include_directories(fuzz_${target} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
    target_link_libraries(fuzz_${target} PRIVATE tessera_render tessera_internals)
    target_link_options(fuzz_${target} PRIVATE -fsanitize=fuzzer)
    set_target_properties(fuzz_${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/fuzz)
  endforeach()
endfunction()
