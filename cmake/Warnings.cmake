# Compiler warnings and sanitizers for the project's own targets. Third-party
# headers are included as SYSTEM so their warnings do not count.

add_library(fireswarm_build_flags INTERFACE)
add_library(fireswarm::build_flags ALIAS fireswarm_build_flags)
target_compile_options(fireswarm_build_flags INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
  -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual
  -Wdouble-promotion -Wimplicit-fallthrough)
# Not -Wnull-dereference: GCC 12 reports it inside inlined Boost.Asio and
# Boost.ProgramOptions code (std::string assignment), depending on inlining, and
# a pragma can only silence it by the header's location. UBSan checks null
# dereferences at run time in the sanitizer build instead.
if(FIRESWARM_WERROR)
  target_compile_options(fireswarm_build_flags INTERFACE -Werror)
endif()

# LLVM's linker in the sanitizer build, where it is installed (scripts/
# install-deps.sh installs it): its executables link about 3.5x faster than with
# GNU ld (server_tests: 1.9 s instead of 6.9). Not in the -O2 build: there GCC 12
# moves unlikely code (a throw's clean-up) to .text.unlikely, and Debian's lld 14
# links it so that an exception thrown from such code is never caught:
# `fireswarm replay` of a garbage log aborted instead of naming it
# (ReplayLog.ErrorsNameTheFile aborts when linked by lld, passes by GNU ld).
find_program(FIRESWARM_LLD ld.lld)
if(FIRESWARM_LLD AND FIRESWARM_SANITIZE)
  add_link_options(-fuse-ld=lld)
endif()

if(FIRESWARM_SANITIZE)
  # Applied globally so every object, test and the executable share one runtime.
  # All of UBSan except -fsanitize=vptr: with GCC 12 it makes LCM 1.3.1's own C++
  # subscription callback (lcm-cpp-impl.hpp, cb_func) see a bogus object and crash,
  # reproduced by a 12-line program that subscribes and publishes on memq:// with no
  # fireswarm code; every other check passes on that program.
  add_compile_options(-fsanitize=address,undefined -fno-sanitize=vptr -fno-omit-frame-pointer
                      -fno-sanitize-recover=all)
  add_link_options(-fsanitize=address,undefined)
endif()

# fireswarm_light_under_sanitizers(<target>): in the sanitizer and fuzz builds,
# <target>'s own code compiles at -O0 instead of -O1. For the test suites, the benchmarks,
# the executable and the server's web adapter: their code drives the libraries,
# which keep -O1 and do the work the tests wait for. Template-heavy code
# (GoogleTest, Boost.Beast) compiles about twice as fast at -O0 under ASan
# (server's web unit: 136 s instead of 281 s).
function(fireswarm_light_under_sanitizers target)
  if(FIRESWARM_SANITIZE OR FIRESWARM_FUZZ)
    target_compile_options(${target} PRIVATE -O0)
  endif()
endfunction()

if(FIRESWARM_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "FIRESWARM_FUZZ needs clang++ for libFuzzer, not "
                        "${CMAKE_CXX_COMPILER_ID}: configure with -DCMAKE_CXX_COMPILER=clang++ "
                        "(scripts/fuzz.sh does)")
  endif()
  # Every object carries libFuzzer's coverage hooks and the sanitizers; only the
  # fuzz targets link libFuzzer itself (-fsanitize=fuzzer, fuzz/CMakeLists.txt).
  # -fno-sanitize=vptr as in FIRESWARM_SANITIZE (LCM's subscription callback).
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=vptr
                      -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=address,undefined)
endif()

# fireswarm_module(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# A module library: public headers in <name>/include/fireswarm/<name>/, private
# sources in <name>/src/. Target fireswarm_<name>, alias fireswarm::<name>.
# A module whose issue has not landed yet has no SOURCES and is an INTERFACE target.
function(fireswarm_module name)
  cmake_parse_arguments(M "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  if(NOT M_SOURCES)
    add_library(fireswarm_${name} INTERFACE)
    add_library(fireswarm::${name} ALIAS fireswarm_${name})
    target_include_directories(fireswarm_${name} INTERFACE ${CMAKE_CURRENT_SOURCE_DIR}/include)
    target_link_libraries(fireswarm_${name} INTERFACE ${M_PUBLIC_DEPS})
    return()
  endif()
  add_library(fireswarm_${name} STATIC ${M_SOURCES})
  add_library(fireswarm::${name} ALIAS fireswarm_${name})
  target_include_directories(fireswarm_${name}
    PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(fireswarm_${name} PUBLIC ${M_PUBLIC_DEPS} PRIVATE ${M_PRIVATE_DEPS} fireswarm::build_flags)
endfunction()
