# Compiler flags every meshtopo target shares: warnings, -Werror, the
# sanitizer build and the fuzzing build. Warnings are applied per target with
# meshtopo_target_flags(target); sanitizers apply to the whole build, so the
# libraries are instrumented as well as the programs that test them.
function(meshtopo_target_flags target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wstrict-prototypes
                         -Wmissing-prototypes -Wno-unused-parameter)
  if(MESHTOPO_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  target_compile_definitions(${target} PRIVATE _POSIX_C_SOURCE=200809L)
endfunction()

if(MESHTOPO_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()

# Fuzzing (libFuzzer, clang only): everything is compiled with coverage
# instrumentation plus ASan and UBSan; only the fuzz executables link the
# libFuzzer driver (-fsanitize=fuzzer, added in tests/fuzz/CMakeLists.txt).
# UBSan must stop at the first error so the fuzzer records the input.
if(MESHTOPO_BUILD_FUZZERS)
  if(NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR
      "MESHTOPO_BUILD_FUZZERS=ON needs clang (libFuzzer), but the C compiler is "
      "${CMAKE_C_COMPILER_ID} (${CMAKE_C_COMPILER}). Configure a fresh build directory with "
      "-DCMAKE_C_COMPILER=clang (Debian: apt-get install clang libclang-rt-14-dev).")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined
                      -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
