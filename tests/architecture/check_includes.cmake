# The library's dependency rule, checked on every include of floorgrid/: each module includes
# only the modules below it, so siblings stay siblings and the core never touches files.
# Usage: cmake -DROOT=<folder holding floorgrid/> -P check_includes.cmake
# Prints every include that breaks the rule and fails when there is one.
cmake_minimum_required(VERSION 3.25)
if(NOT ROOT)
  message(FATAL_ERROR "check_includes: give -DROOT=<folder holding floorgrid/>")
endif()

# module -> the modules it may include (besides itself). io/ is the only code that touches
# files; apps/ (the CLI) and server/ sit on top and are never included by the library.
set(allowed_core "")
set(allowed_geometry core)
set(allowed_maps core geometry)
set(allowed_robot core geometry)
set(allowed_localization core geometry maps robot)
set(allowed_mapping core geometry)
set(allowed_evaluation core geometry maps mapping)
set(allowed_simulation core geometry maps robot)
set(allowed_pipeline core geometry maps robot localization mapping evaluation)
set(allowed_io core geometry maps robot localization mapping evaluation simulation pipeline)
set(allowed_server core geometry maps robot localization mapping evaluation simulation pipeline
                   io)
# The integrator's surface (floorgrid/floorgrid.hpp and .cpp, at the top of floorgrid/) sits on
# the library; nothing in it includes the surface.
set(allowed_surface core geometry maps robot localization mapping evaluation simulation pipeline
                    io)
set(known core geometry maps robot localization mapping evaluation simulation pipeline io server
          surface)
# File formats are io/'s: no other module includes a format library's headers.
set(format_modules io server)

file(GLOB_RECURSE files RELATIVE "${ROOT}/floorgrid" "${ROOT}/floorgrid/*.hpp"
     "${ROOT}/floorgrid/*.cpp")
list(SORT files)
set(violations 0)
foreach(file ${files})
  string(REGEX MATCH "^[^/]+" module "${file}")
  if(NOT file MATCHES "/")
    set(module surface)
  endif()
  if(NOT module IN_LIST known)
    message("floorgrid/${file}: module '${module}' has no place in the dependency rule "
            "(tests/architecture/check_includes.cmake)")
    math(EXPR violations "${violations} + 1")
    continue()
  endif()
  if(NOT module IN_LIST format_modules)
    file(STRINGS "${ROOT}/floorgrid/${file}" format_includes
         REGEX "^[ \t]*#[ \t]*include[ \t]*<(nlohmann/|yaml-cpp/|png\\.h|zlib\\.h)")
    foreach(line ${format_includes})
      string(STRIP "${line}" line)
      message("floorgrid/${file}: ${module}/ must not include a file format's library (${line})")
      math(EXPR violations "${violations} + 1")
    endforeach()
  endif()
  file(STRINGS "${ROOT}/floorgrid/${file}" includes
       REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<](floorgrid|apps)/")
  foreach(line ${includes})
    string(REGEX MATCH "(floorgrid|apps)/[^/\">]+" target "${line}")
    string(REGEX REPLACE "^floorgrid/" "" target_module "${target}")
    if(target_module MATCHES "\\.(hpp|cpp)$")
      set(target_module surface)
    endif()
    if(target_module STREQUAL module)
      continue()
    endif()
    if(target MATCHES "^apps/" OR NOT target_module IN_LIST allowed_${module})
      string(STRIP "${line}" line)
      message("floorgrid/${file}: ${module}/ must not include ${target}/ (${line})")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
endforeach()

list(LENGTH files count)
if(violations GREATER 0)
  message(FATAL_ERROR "check_includes: ${violations} include(s) break the dependency rule")
endif()
message("check_includes: ${count} files follow the dependency rule")
