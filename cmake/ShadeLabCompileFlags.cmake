# The compile options of every ShadeLab target, for the project's build and the ParaView plugin's
# (paraview/), so that the two compute the same bits: C++17, a Release build unless told
# otherwise, and the options below.
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
if(NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
  set(CMAKE_BUILD_TYPE Release CACHE STRING "Build type" FORCE)
endif()
# The kernel's loops are written for the compiler to vectorise. Built for the instructions
# of the machine that builds it (AVX2 or AVX-512 where present) rather than the x86-64
# baseline (SSE2), the complete model runs about twice as fast. Every ShadeLab target gets the
# flag, so that an inline function of ShadeLab's headers is compiled alike wherever it is used.
# The binaries and the installed library then need such a processor: turn the option off to
# build for other machines.
option(SHADELAB_NATIVE_ARCH "Compile for the building machine's instruction set (-march=native)" ON)
if(SHADELAB_NATIVE_ARCH)
  include(CheckCXXCompilerFlag)
  check_cxx_compiler_flag(-march=native compiler_accepts_march_native)
  if(compiler_accepts_march_native)
    # GCC 12.2 (Debian 12's compiler) builds some vectors of doubles wrongly for processors
    # with AVX-512: {x, x, 0, 0} becomes {x, x, x, x} (a 256-bit broadcast where a 128-bit one
    # was meant), which struck the tests' own arrays. It comes of AVX-512 and, on some
    # processors (Rocket Lake), of the tuning for them even without AVX-512. Where this program
    # shows it on the machine that builds, ShadeLab's code is built without AVX-512 and tuned
    # generically (AVX2 stays; the results are the same bits, as there is no fused multiply-add;
    # Embree keeps its own AVX-512 kernels); where that is not enough, for the x86-64 baseline.
    set(vectors_check [=[
      #include <vector>
      struct Values { int type = 1; std::vector<double> reals; };
      Values made(std::vector<double> values) { Values v; v.reals = std::move(values); return v; }
      int main() { const double x = 1.0; return made({ x, x, 0.0, 0.0 }).reals[2] == 0.0 ? 0 : 1; }
    ]=])
    include(CheckCXXSourceRuns)
    # Checked at -O2 and -O3 alike: the case has gone wrong at one and not the other.
    function(shadelab_check_vectors flags result)
      set(CMAKE_REQUIRED_FLAGS "-O2 ${flags}")
      check_cxx_source_runs("${vectors_check}" ${result}_O2)
      set(CMAKE_REQUIRED_FLAGS "-O3 ${flags}")
      check_cxx_source_runs("${vectors_check}" ${result}_O3)
      if(${result}_O2 AND ${result}_O3)
        set(${result} TRUE PARENT_SCOPE)
      else()
        set(${result} FALSE PARENT_SCOPE)
      endif()
    endfunction()
    shadelab_check_vectors("-march=native" shadelab_native_vectors_built_right)
    if(NOT shadelab_native_vectors_built_right)
      shadelab_check_vectors("-march=native -mno-avx512f -mtune=generic" shadelab_generic_tuned_vectors_built_right)
    endif()
    if(shadelab_native_vectors_built_right)
      add_compile_options(-march=native)
    elseif(shadelab_generic_tuned_vectors_built_right)
      message(STATUS "ShadeLab: this compiler builds some vectors wrongly for this processor; compiling with "
        "-march=native -mno-avx512f -mtune=generic")
      add_compile_options(-march=native -mno-avx512f -mtune=generic)
    else()
      message(WARNING "ShadeLab: this compiler builds some vectors wrongly for this processor, even without "
        "AVX-512 and with generic tuning; compiling for the x86-64 baseline, which is slower")
    endif()
  endif()
endif()
# No fused multiply-add anywhere (GCC contracts a * b + c into one by default where the
# instruction set has it): results are the same bits whatever instructions a machine has.
add_compile_options(-ffp-contract=off)
