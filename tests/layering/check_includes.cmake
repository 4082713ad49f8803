# The include rules of the layers (README, "Layout and layers"), checked on every
# `#include "..."` of the library and command sources:
#   cmake -DSOURCE_DIR=<repo> [-DPLANT=<file>:<header>] -P check_includes.cmake
# A file may include headers of its own folder and of the folders listed for it below; an
# include that names no existing file, and a source in a folder not listed, are errors too.
# PLANT pretends <file> also includes <header>: the planted-include test uses it to show
# that a forbidden include fails (ctest layering/planted_include passes when the check names it).

# Folders a folder's files may include, besides their own. Lower layers first.
set(io_lib io/base io/mocap io/gait io/video)
set(prior_lib prior/numerics prior/learning prior/model prior/eval prior/motion)
set(tracker_lib tracker/body tracker/clip tracker/frames tracker/state tracker/filter tracker/run)

set(allowed_io/base "")
set(allowed_io/mocap io/base)
set(allowed_io/gait io/base io/mocap)
set(allowed_io/video io/base)
set(allowed_io/cli ${io_lib})

set(allowed_calibration ${io_lib})
set(allowed_calibration/cli ${io_lib} io/cli calibration)

set(allowed_prior/numerics ${io_lib})
set(allowed_prior/learning ${io_lib} prior/numerics)
set(allowed_prior/model ${io_lib} prior/numerics prior/learning)
set(allowed_prior/eval ${io_lib} prior/numerics prior/learning prior/model)
set(allowed_prior/motion ${io_lib} prior/numerics prior/learning prior/model)
set(allowed_prior/cli ${io_lib} io/cli ${prior_lib})

set(below_tracker ${io_lib} calibration ${prior_lib})
set(allowed_tracker/body ${below_tracker})
set(allowed_tracker/clip ${below_tracker} tracker/body)
set(allowed_tracker/frames ${below_tracker} tracker/body tracker/clip)
set(allowed_tracker/state ${below_tracker})
set(allowed_tracker/filter ${below_tracker} tracker/body tracker/clip tracker/frames tracker/state)
set(allowed_tracker/run ${below_tracker} ${tracker_lib})
# The `jgpm` command (main.cc sees every layer's command group).
set(allowed_tracker/cli ${below_tracker} ${tracker_lib} io/cli calibration/cli prior/cli)
# The Python module (`import jgpm`) binds every layer's library, and the walkers' reader
# and calibration of `calibrate --walkers`.
set(allowed_tracker/python ${below_tracker} ${tracker_lib} io/cli calibration/cli tracker/cli)

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "give -DSOURCE_DIR=<the repository>")
endif()
file(GLOB_RECURSE files RELATIVE ${SOURCE_DIR}
  ${SOURCE_DIR}/io/*.h ${SOURCE_DIR}/io/*.cc
  ${SOURCE_DIR}/calibration/*.h ${SOURCE_DIR}/calibration/*.cc
  ${SOURCE_DIR}/prior/*.h ${SOURCE_DIR}/prior/*.cc
  ${SOURCE_DIR}/tracker/*.h ${SOURCE_DIR}/tracker/*.cc)
if(files STREQUAL "")
  message(FATAL_ERROR "${SOURCE_DIR}: no sources found")
endif()

set(errors 0)
foreach(file IN LISTS files)
  get_filename_component(folder ${file} DIRECTORY)
  if(NOT DEFINED allowed_${folder})
    message(SEND_ERROR "${file}: folder ${folder} has no include rule (add it to tests/layering/check_includes.cmake and the README)")
    math(EXPR errors "${errors} + 1")
    continue()
  endif()
  file(STRINGS ${SOURCE_DIR}/${file} lines REGEX "^#include \"")
  if(PLANT MATCHES "^${file}:(.+)$")
    list(APPEND lines "#include \"${CMAKE_MATCH_1}\"")
  endif()
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*$" "\\1" header "${line}")
    if(NOT EXISTS ${SOURCE_DIR}/${header})
      message(SEND_ERROR "${file}: includes \"${header}\", which is not a file of the project")
      math(EXPR errors "${errors} + 1")
      continue()
    endif()
    get_filename_component(header_folder ${header} DIRECTORY)
    if(header_folder STREQUAL folder)
      continue()
    endif()
    list(FIND allowed_${folder} "${header_folder}" at)
    if(at EQUAL -1)
      set(others "${allowed_${folder}}")
      if(others STREQUAL "")
        set(others "nothing else")
      endif()
      message(SEND_ERROR "${file}: includes \"${header}\": ${folder} may include only ${folder}/ and ${others}")
      math(EXPR errors "${errors} + 1")
    endif()
  endforeach()
endforeach()
list(LENGTH files count)
if(errors GREATER 0)
  message(FATAL_ERROR "${errors} forbidden or broken include(s) in ${count} files")
endif()
message(STATUS "${count} files: every include is allowed")
