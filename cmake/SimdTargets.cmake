# SIMD kernels are compiled once per instruction set and picked at run time,
# so one binary runs on any x86-64 and uses the widest vectors it finds.
#
# tessera_add_simd_kernels(<target> SOURCES <file.cpp>...) builds the sources three
# times as OBJECT libraries <target>_sse4 / _avx2 / _avx512, each with its own -march
# and TESSERA_SIMD_ARCH set to the matching xsimd architecture type, and adds their
# objects to <target>. A kernel source instantiates its templates for
# TESSERA_SIMD_ARCH and names its entry points with TESSERA_SIMD_SUFFIX.
# With NO_FP_CONTRACT, a*b + c is never fused into an FMA, so the kernels
# compute exactly what scalar code built without FMA does (the rasterizer's
# kernels must match its scalar loop bit for bit).
set(TESSERA_SIMD_LEVELS sse4 avx2 avx512)
set(TESSERA_SIMD_MARCH_sse4 x86-64-v2)
set(TESSERA_SIMD_MARCH_avx2 x86-64-v3)
set(TESSERA_SIMD_MARCH_avx512 x86-64-v4)
set(TESSERA_SIMD_ARCH_sse4 "xsimd::sse4_2")
set(TESSERA_SIMD_ARCH_avx2 "xsimd::fma3<xsimd::avx2>")
set(TESSERA_SIMD_ARCH_avx512 "xsimd::avx512bw")

# A test build for machines without AVX-512 (cf. tools/ci/check_avx512_emulated.sh):
# the avx512 copies are compiled for x86-64-v3 with SIMDe's portable AVX-512
# intrinsics (src/simd/avx512_emulation.hpp), and the run-time ISA detection
# reports avx512 as available, so the every-ISA tests run those copies too.
# Never for a release: the emulated kernels are slow, and they test the kernels'
# logic, not the compiler's real AVX-512 code.
option(TESSERA_EMULATE_AVX512 "Test build: run the AVX-512 kernels on any x86-64-v3 CPU through SIMDe emulation" OFF)
if(TESSERA_EMULATE_AVX512)
  find_path(TESSERA_SIMDE_INCLUDE_DIR simde/x86/avx512.h)
  if(NOT TESSERA_SIMDE_INCLUDE_DIR)
    message(FATAL_ERROR "TESSERA_EMULATE_AVX512 needs SIMDe (Debian: apt-get install libsimde-dev)")
  endif()
  set(TESSERA_SIMD_MARCH_avx512 x86-64-v3)
  message(STATUS "AVX-512 kernels: emulated with SIMDe (${TESSERA_SIMDE_INCLUDE_DIR}); test build only")
endif()

function(tessera_add_simd_kernels target)
  cmake_parse_arguments(ARG "NO_FP_CONTRACT" "" "SOURCES;LINK" ${ARGN})
  # The lowest ISA comes first in link order: inline functions shared between
  # the copies must resolve to code every x86-64 machine can run.
  foreach(level IN LISTS TESSERA_SIMD_LEVELS)
    set(obj ${target}_${level})
    add_library(${obj} OBJECT ${ARG_SOURCES})
    target_link_libraries(${obj} PRIVATE xsimd glm::glm tessera_warnings ${ARG_LINK})
    target_include_directories(${obj} PRIVATE ${PROJECT_SOURCE_DIR}/include ${PROJECT_SOURCE_DIR}/src)
    target_compile_definitions(${obj} PRIVATE
      "TESSERA_SIMD_ARCH=${TESSERA_SIMD_ARCH_${level}}"
      "TESSERA_SIMD_SUFFIX=${level}")
    target_compile_options(${obj} PRIVATE
      -march=${TESSERA_SIMD_MARCH_${level}} -mtune=generic
      # g++ 12 warns falsely inside avx512fintrin.h, and cannot build AVX-512 code at -O0.
      -Wno-maybe-uninitialized $<$<CONFIG:Debug>:-Og>)
    if(TESSERA_EMULATE_AVX512 AND level STREQUAL "avx512")
      target_compile_definitions(${obj} PRIVATE TESSERA_EMULATE_AVX512)
      target_include_directories(${obj} SYSTEM PRIVATE ${TESSERA_SIMDE_INCLUDE_DIR})
      # 512-bit vector arguments without AVX-512 change the ABI (-Wpsabi): they are
      # only passed between inline functions of one object here.
      # -ffp-contract=off: SIMDe splits each 512-bit operation into two 256-bit
      # ones through unions, and g++ then fuses a*b + c into an FMA in some
      # inlined copies of an expression and not in others, so two paths of one
      # kernel that the real build keeps bit-identical differ in the last bit
      # (seen in shade_fragment_runs vs shade_fragments; real AVX-512 code did the
      # same, so shade_kernels_simd.cpp is now built without contraction everywhere).
      # Explicit fma() stays fused.
      target_compile_options(${obj} PRIVATE -Wno-psabi -ffp-contract=off)
    endif()
    if(ARG_NO_FP_CONTRACT)
      target_compile_options(${obj} PRIVATE -ffp-contract=off)
    endif()
    set_target_properties(${obj} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    target_sources(${target} PRIVATE $<TARGET_OBJECTS:${obj}>)
  endforeach()
endfunction()
