# Third-party packages, all from Debian 12 (scripts/install-deps.sh installs them).
# Packages without a usable CMake config are wrapped in IMPORTED/INTERFACE targets
# here, once, so modules only ever link to fireswarm::third_party::<name>.

find_package(Threads REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(Boost 1.74 REQUIRED CONFIG COMPONENTS system program_options)
find_package(box2d 2.4 REQUIRED CONFIG)
find_package(nlohmann_json 3 REQUIRED CONFIG)
find_package(yaml-cpp REQUIRED CONFIG)
find_package(spdlog REQUIRED CONFIG)
# The command center's web adapter: TLS (Boost.Asio SSL over OpenSSL), MBTiles map tiles.
find_package(OpenSSL 3 REQUIRED)
find_package(SQLite3 REQUIRED)

# OMPL: variables only; ompl.pc would inject -std=c++14, so it is not used.
find_package(ompl 1.5 REQUIRED)
add_library(fireswarm_third_party_ompl INTERFACE)
target_include_directories(fireswarm_third_party_ompl SYSTEM INTERFACE ${OMPL_INCLUDE_DIRS})
target_link_libraries(fireswarm_third_party_ompl INTERFACE ${OMPL_LIBRARIES})
add_library(fireswarm::third_party::ompl ALIAS fireswarm_third_party_ompl)

# GeographicLib 2.1 ships its find module outside the default module path.
list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
find_package(GeographicLib REQUIRED)
add_library(fireswarm_third_party_geographiclib INTERFACE)
target_include_directories(fireswarm_third_party_geographiclib SYSTEM INTERFACE ${GeographicLib_INCLUDE_DIRS})
target_link_libraries(fireswarm_third_party_geographiclib INTERFACE ${GeographicLib_LIBRARIES})
add_library(fireswarm::third_party::geographiclib ALIAS fireswarm_third_party_geographiclib)

# LCM 1.3.1 has no CMake config and its lcm.pc needs glib: find the pieces by hand.
find_program(LCM_GEN lcm-gen REQUIRED)
find_path(LCM_INCLUDE_DIR lcm/lcm-cpp.hpp REQUIRED)
find_library(LCM_LIBRARY lcm REQUIRED)
add_library(fireswarm::third_party::lcm UNKNOWN IMPORTED)
set_target_properties(fireswarm::third_party::lcm PROPERTIES
  IMPORTED_LOCATION ${LCM_LIBRARY}
  INTERFACE_INCLUDE_DIRECTORIES ${LCM_INCLUDE_DIR})

if(FIRESWARM_BUILD_TESTS)
  find_package(GTest REQUIRED CONFIG)
  include(GoogleTest)
endif()
if(FIRESWARM_BUILD_BENCH)
  find_package(benchmark REQUIRED CONFIG)
endif()
