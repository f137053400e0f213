# Included by the top-level CMakeLists.txt when TLOD_FUZZ is on, before any library is added:
# every tesslod target (core, lod, backends, the importers) is compiled with libFuzzer's
# coverage instrumentation plus ASan and UBSan, so a fuzz target sees edges and memory errors
# in the library code it calls, not only in the harness. The fuzz targets themselves link
# libFuzzer (fuzz/CMakeLists.txt). See docs/fuzzing.md.
if(NOT CMAKE_C_COMPILER_ID STREQUAL "Clang" OR NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "TLOD_FUZZ needs clang and clang++ (libFuzzer); use the 'fuzz' preset "
                      "(cmake --preset fuzz) or set CMAKE_C_COMPILER=clang CMAKE_CXX_COMPILER=clang++")
endif()
if(TLOD_SANITIZE)
  message(FATAL_ERROR "TLOD_FUZZ already builds with ASan and UBSan; leave TLOD_SANITIZE off")
endif()
# -fno-sanitize-recover: a UBSan report (signed overflow, misaligned load, bad shift) stops
# the run like an ASan report, so libFuzzer saves the input as a crash.
set(TLOD_FUZZ_COMPILE_FLAGS -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                            -fno-omit-frame-pointer -g)
target_compile_options(tlod_build_flags INTERFACE ${TLOD_FUZZ_COMPILE_FLAGS})
target_link_options(tlod_build_flags INTERFACE -fsanitize=address,undefined)
