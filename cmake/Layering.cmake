# fireswarm_check_layering(<module> "<allowed modules>" ...): DESIGN.md's "who may
# include whom" as a configure-time check. Every module's own links (public and
# private) may name only the modules its line allows ("-": none); a module reaches headers only
# through what it links, so this also keeps its includes in line. Third-party
# targets (fireswarm::third_party::*) and fireswarm::build_flags are not modules.
function(fireswarm_check_layering)
  set(args ${ARGN})
  list(LENGTH args count)
  math(EXPR last "${count} - 1")
  foreach(i RANGE 0 ${last} 2)
    math(EXPR j "${i} + 1")
    list(GET args ${i} module)
    list(GET args ${j} allowed)
    separate_arguments(allowed)
    get_target_property(type fireswarm_${module} TYPE)
    if(type STREQUAL "INTERFACE_LIBRARY")
      get_target_property(links fireswarm_${module} INTERFACE_LINK_LIBRARIES)
    else()
      get_target_property(links fireswarm_${module} LINK_LIBRARIES)
    endif()
    if(NOT links)
      set(links "")
    endif()
    foreach(link IN LISTS links)
      if(link MATCHES "^fireswarm::([a-z0-9_]+)$" AND NOT CMAKE_MATCH_1 STREQUAL "build_flags")
        if(NOT CMAKE_MATCH_1 IN_LIST allowed)
          message(FATAL_ERROR "layering: module '${module}' links '${CMAKE_MATCH_1}', which "
                              "DESIGN.md does not allow (allowed: ${allowed})")
        endif()
      endif()
    endforeach()
  endforeach()
endfunction()
