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
# io/ holds only folders, one per concept, each including the library below io/ (allowed_io)
# and the io/ folders listed for it: bytes and text files; our own formats and maps; drawings
# (DXF); robot logs; the report; datasets; exports; options; whole jobs.
set(io_folders files formats plans logs report dataset export options jobs)
set(allowed_io_files "")
set(allowed_io_formats files)
set(allowed_io_plans files formats)
set(allowed_io_logs files)
set(allowed_io_report files)
set(allowed_io_dataset files formats plans logs)
set(allowed_io_export files formats report dataset)
set(allowed_io_options files dataset)
set(allowed_io_jobs files formats plans logs report dataset export options)
set(known core geometry maps robot localization mapping evaluation simulation pipeline server
          surface)
foreach(folder ${io_folders})
  list(APPEND known io/${folder})
endforeach()

file(GLOB_RECURSE files RELATIVE "${ROOT}/floorgrid" "${ROOT}/floorgrid/*.hpp"
     "${ROOT}/floorgrid/*.cpp")
list(SORT files)
set(violations 0)
foreach(file ${files})
  string(REGEX MATCH "^[^/]+" module "${file}")
  if(NOT file MATCHES "/")
    set(module surface)
  elseif(module STREQUAL "io")
    # io/<folder>/file: the folder is the module; a file right in io/ has none.
    string(REGEX MATCH "^io/[^/]+/" module "${file}")
    string(REGEX REPLACE "/$" "" module "${module}")
  endif()
  if(NOT module OR NOT module IN_LIST known)
    message("floorgrid/${file}: module '${module}' has no place in the dependency rule (io/ "
            "holds only its concept folders: ${io_folders}) "
            "(tests/architecture/check_includes.cmake)")
    math(EXPR violations "${violations} + 1")
    continue()
  endif()
  # File formats are io/'s: no other module includes a format library's headers.
  if(NOT module MATCHES "^(io/|server$)")
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
    if(target_module STREQUAL "io")
      # An io/ header: its folder is its module.
      string(REGEX MATCH "floorgrid/io/[^/\">]+/" target "${line}")
      string(REGEX REPLACE "^floorgrid/|/$" "" target_module "${target}")
      if(NOT target_module IN_LIST known)
        string(STRIP "${line}" line)
        message("floorgrid/${file}: io/ holds its headers in its folders (${line})")
        math(EXPR violations "${violations} + 1")
        continue()
      endif()
    endif()
    if(target_module STREQUAL module)
      continue()
    endif()
    if(module MATCHES "^io/")
      # An io/ folder: the library below io/, and the io/ folders listed for it.
      string(REGEX REPLACE "^io/" "" folder "${module}")
      string(REGEX REPLACE "^io/" "" target_folder "${target_module}")
      if(target_module MATCHES "^io/")
        set(allowed_here ${allowed_io_${folder}})
        set(checked ${target_folder})
      else()
        set(allowed_here ${allowed_io})
        set(checked ${target_module})
      endif()
    else()
      # Every other module sees io/ as one: io/<folder> is allowed where io is.
      set(allowed_here ${allowed_${module}})
      string(REGEX REPLACE "^io/.*" "io" checked "${target_module}")
    endif()
    if(target MATCHES "^apps/" OR NOT checked IN_LIST allowed_here)
      string(STRIP "${line}" line)
      message("floorgrid/${file}: ${module}/ must not include ${target_module}/ (${line})")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
endforeach()

list(LENGTH files count)
if(violations GREATER 0)
  message(FATAL_ERROR "check_includes: ${violations} include(s) break the dependency rule")
endif()
message("check_includes: ${count} files follow the dependency rule")
