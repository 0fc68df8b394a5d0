# syncap_add_library(<name>
#                    [SOURCES <file>...]     without sources: a header-only (INTERFACE) library
#                    [INCLUDE_ROOT <dir>]    default: ${SYNCAP_INCLUDE_ROOT}, set once per part
#                    [PUBLIC <dep>...]       (host/src, edge/src, firmware/include, ...)
#                    [PRIVATE <dep>...]
#                    [DEFINITIONS <def>...]) private compile definitions
# Every library of the project in one pattern: its include root (users include
# "<folder>/<file>.hpp" from it), its dependencies and the project's warnings
# (syncap_target_warnings), set in one place so that no two libraries differ by accident.
function(syncap_add_library name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "INCLUDE_ROOT" "SOURCES;PUBLIC;PRIVATE;DEFINITIONS")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "syncap_add_library(${name}): unknown arguments ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT arg_INCLUDE_ROOT)
    set(arg_INCLUDE_ROOT ${SYNCAP_INCLUDE_ROOT})
  endif()
  if(NOT arg_INCLUDE_ROOT)
    message(FATAL_ERROR "syncap_add_library(${name}): no INCLUDE_ROOT and no SYNCAP_INCLUDE_ROOT "
                        "in ${CMAKE_CURRENT_SOURCE_DIR}")
  endif()
  cmake_path(ABSOLUTE_PATH arg_INCLUDE_ROOT NORMALIZE)
  if(NOT arg_SOURCES)
    if(arg_PRIVATE OR arg_DEFINITIONS)
      message(FATAL_ERROR "syncap_add_library(${name}): a header-only library has no PRIVATE part")
    endif()
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${arg_INCLUDE_ROOT})
    target_link_libraries(${name} INTERFACE ${arg_PUBLIC})
    return()
  endif()
  add_library(${name} STATIC ${arg_SOURCES})
  target_include_directories(${name} PUBLIC ${arg_INCLUDE_ROOT})
  target_link_libraries(${name} PUBLIC ${arg_PUBLIC} PRIVATE ${arg_PRIVATE})
  if(arg_DEFINITIONS)
    target_compile_definitions(${name} PRIVATE ${arg_DEFINITIONS})
  endif()
  syncap_target_warnings(${name})
endfunction()
