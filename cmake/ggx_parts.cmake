# The optional parts of the build (the command, the Python package, the examples, the tests, the fuzz targets, the
# CUDA build): each is a cache option GGX_... with the value AUTO (the default), ON or OFF.
#  - AUTO: the part is built when its dependencies are found, and otherwise turns itself off with one STATUS line
#    naming what is missing and its Debian package. In a project that includes libggx with add_subdirectory or
#    FetchContent, AUTO leaves every part off (one STATUS line says so): such a project gets the library only.
#  - ON: the part is required; a missing dependency stops the configure with the same message.
#  - OFF: not built, and nothing is looked for.
# A normal variable a parent project sets before add_subdirectory takes the place of the default. After
# ggx_part_resolve the variable holds ON or OFF (a normal variable over the cache entry), so if(GGX_BUILD_TOOL) and the
# subdirectories see the result.

# ggx_part(VAR DOC): declares the option VAR and sets VAR_MODE to AUTO, ON or OFF.
macro(ggx_part var doc)
  if(DEFINED ${var})
    set(_ggx_value "${${var}}")
  else()
    set(_ggx_value AUTO)
  endif()
  set(${var} "${_ggx_value}" CACHE STRING "${doc}: AUTO (when its dependencies are found), ON (required) or OFF")
  set_property(CACHE ${var} PROPERTY STRINGS AUTO ON OFF)
  string(TOUPPER "${_ggx_value}" _ggx_value)
  if(_ggx_value STREQUAL "AUTO")
    set(${var}_MODE AUTO)
  elseif(_ggx_value MATCHES "^(ON|TRUE|YES|Y|1)$")
    set(${var}_MODE ON)
  elseif(_ggx_value MATCHES "^(OFF|FALSE|NO|N|0)$")
    set(${var}_MODE OFF)
  else()
    message(FATAL_ERROR "${var} is '${${var}}': it takes AUTO, ON or OFF")
  endif()
  # Until it is resolved, the part counts as wanted unless it is OFF.
  if(${var}_MODE STREQUAL "OFF")
    set(${var} OFF)
  else()
    set(${var} ON)
  endif()
endmacro()

# ggx_part_wanted(VAR OUT): OUT is TRUE when VAR's dependencies are worth looking for (ON, or AUTO in the top-level
# project); an AUTO part of a subproject is switched off here, quietly (ggx_parts_report says it once).
macro(ggx_part_wanted var out)
  if(${var}_MODE STREQUAL "ON" OR (${var}_MODE STREQUAL "AUTO" AND GGX_IS_TOP_LEVEL))
    set(${out} TRUE)
  else()
    set(${out} FALSE)
    if(${var}_MODE STREQUAL "AUTO")
      list(APPEND GGX_PARTS_LEFT_OUT ${var})
    endif()
    set(${var} OFF)
  endif()
endmacro()

# ggx_part_resolve(VAR LABEL FOUND MISSING): after ggx_part_wanted gave TRUE and the dependencies were looked for,
# FOUND (a boolean value) says whether they are there and MISSING names what is not (with the Debian package).
macro(ggx_part_resolve var label found missing)
  if(${found})
    set(${var} ON)
  elseif(${var}_MODE STREQUAL "ON")
    message(FATAL_ERROR "${var} is ON but ${missing}. Install it, or configure with -D${var}=AUTO (build it only when "
                        "it is found) or -D${var}=OFF.")
  else()
    message(STATUS "${label}: off (${missing})")
    set(${var} OFF)
  endif()
endmacro()

# ggx_parts_report(): the one line of a subproject whose AUTO parts stayed off.
function(ggx_parts_report)
  if(GGX_PARTS_LEFT_OUT)
    string(REPLACE ";" ", " parts "${GGX_PARTS_LEFT_OUT}")
    message(STATUS "ggx: included by another project, so ${parts} (AUTO) stay off: set one ON to build it")
  endif()
endfunction()
