# Runs at install time, for the prefix actually installed into: says where the Python package went and whether
# python3 finds it there (Debian's searches <prefix>/lib/python3.X/dist-packages for /usr/local and /usr), or the
# PYTHONPATH to set. Inputs (CMakeLists.txt's install(CODE)): GGX_PYTHON (the interpreter, or empty) and
# GGX_PYTHON_INSTALL_DIR (relative to the prefix or absolute).
if(IS_ABSOLUTE "${GGX_PYTHON_INSTALL_DIR}")
  set(pydir "${GGX_PYTHON_INSTALL_DIR}")
else()
  set(pydir "${CMAKE_INSTALL_PREFIX}/${GGX_PYTHON_INSTALL_DIR}")
endif()
set(found FALSE)
if(GGX_PYTHON AND NOT DEFINED ENV{DESTDIR})
  execute_process(COMMAND env -u PYTHONPATH "${GGX_PYTHON}" -c
                          "import os, sys; print(os.path.realpath(sys.argv[1]) in map(os.path.realpath, sys.path))"
                          "${pydir}"
                  OUTPUT_VARIABLE out OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(out STREQUAL "True")
    set(found TRUE)
  endif()
endif()
if(DEFINED ENV{DESTDIR} AND NOT "$ENV{DESTDIR}" STREQUAL "")
  message(STATUS "Python package ggx: staged in $ENV{DESTDIR}${pydir}/ggx (installed, it is ${pydir}/ggx)")
elseif(found)
  message(STATUS "Python package ggx: ${pydir}/ggx (${GGX_PYTHON} finds it: import ggx)")
else()
  include("${CMAKE_CURRENT_LIST_DIR}/sh_quote.cmake")
  ggx_sh_quote(q "${pydir}")
  message(STATUS "Python package ggx: ${pydir}/ggx; python3 does not search that folder: "
                 "export PYTHONPATH=${q}")
endif()
