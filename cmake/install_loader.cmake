# Runs at install time (make install, cmake --install [--prefix P]), for the prefix actually installed into, so that a
# freshly installed program finds the shared library (GGX_SONAME_FILE, libggx.so.0.1) without LD_LIBRARY_PATH:
#  - libdir is a folder the dynamic loader searches (ld.so.conf: /usr/local/lib, /usr/lib/<triplet>, ...): as root
#    and without DESTDIR, run ldconfig, which the loader's cache needs to list a new library;
#  - any other libdir ($HOME/.local/lib, /opt/x/lib): ggx.pc's Libs carry -Wl,-rpath,${libdir}.
# It then writes ggx.pc for that prefix and says what a user still has to set (PKG_CONFIG_PATH, ldconfig as root).
# Inputs (set by CMakeLists.txt's install(CODE)): GGX_PC_IN, GGX_BINARY_DIR, GGX_LIBDIR and GGX_INCLUDEDIR (relative to
# the prefix or absolute), GGX_VERSION, GGX_DESCRIPTION, GGX_SONAME_FILE (empty for a static libggx: no loader, no
# rpath), GGX_LDCONFIG and GGX_PKG_CONFIG (paths or empty).
cmake_policy(PUSH)
cmake_policy(SET CMP0057 NEW) # IN_LIST
include("${CMAKE_CURRENT_LIST_DIR}/sh_quote.cmake")
if(IS_ABSOLUTE "${GGX_LIBDIR}")
  set(libdir "${GGX_LIBDIR}")
else()
  set(libdir "${CMAKE_INSTALL_PREFIX}/${GGX_LIBDIR}")
endif()
get_filename_component(libdir_real "${libdir}" REALPATH)

# The loader's folders, as ldconfig lists them (-N: no cache update, -X: no links; readable without root).
set(in_loader FALSE)
if(GGX_SONAME_FILE STREQUAL "")
  set(in_loader TRUE) # a static library: nothing for the loader to find
elseif(GGX_LDCONFIG)
  execute_process(COMMAND "${GGX_LDCONFIG}" -v -N -X OUTPUT_VARIABLE ld_out ERROR_QUIET)
  string(REPLACE "\n" ";" ld_lines "${ld_out}")
  foreach(line IN LISTS ld_lines)
    if(line MATCHES "^(/[^:]*):")
      get_filename_component(dir_real "${CMAKE_MATCH_1}" REALPATH)
      if(dir_real STREQUAL libdir_real)
        set(in_loader TRUE)
      endif()
    endif()
  endforeach()
  # ldconfig lists only folders that exist; a first install into /usr/local/lib may create it. The loader's
  # configuration names them, so read that when the folder is new.
  if(NOT in_loader AND NOT EXISTS "${libdir}")
    file(GLOB confs /etc/ld.so.conf.d/*.conf)
    foreach(conf IN LISTS confs)
      file(STRINGS "${conf}" dirs REGEX "^/")
      foreach(d IN LISTS dirs)
        string(STRIP "${d}" d)
        if(d STREQUAL libdir)
          set(in_loader TRUE)
        endif()
      endforeach()
    endforeach()
  endif()
endif()

set(GGX_PC_RPATH "")
set(GGX_PC_LIBS "")
set(notes "")
if(GGX_SONAME_FILE STREQUAL "")
  # A static libggx: a program links its dependencies too, with or without pkg-config --static.
  set(GGX_PC_LIBS " -lm -lpthread")
elseif(in_loader)
  execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if("$ENV{DESTDIR}" STREQUAL "" AND uid STREQUAL "0")
    set(run_ldconfig TRUE) # after the library is in place: below
  elseif("$ENV{DESTDIR}" STREQUAL "")
    list(APPEND notes "run ldconfig as root so that programs find ${GGX_SONAME_FILE} in ${libdir}")
  endif()
else()
  set(GGX_PC_RPATH " -Wl,-rpath,\${libdir}")
endif()

# ggx.pc for this prefix (@ONLY: the file's own ${prefix} references stay).
ggx_pc_escape(GGX_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
foreach(d LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${GGX_${d}}")
    ggx_pc_escape(GGX_PC_${d} "${GGX_${d}}")
  else()
    set(GGX_PC_${d} "\${prefix}/${GGX_${d}}")
  endif()
endforeach()
configure_file("${GGX_PC_IN}" "${GGX_BINARY_DIR}/pc-install/ggx.pc" @ONLY)
file(INSTALL "${GGX_BINARY_DIR}/pc-install/ggx.pc" DESTINATION "${libdir}/pkgconfig")

if(run_ldconfig)
  execute_process(COMMAND "${GGX_LDCONFIG}" RESULT_VARIABLE rc)
  if(rc EQUAL 0)
    message(STATUS "Ran ldconfig: the loader now finds ${GGX_SONAME_FILE} in ${libdir}")
  else()
    list(APPEND notes "ldconfig failed (${rc}): run it as root so that programs find ${GGX_SONAME_FILE}")
  endif()
elseif(NOT in_loader)
  message(STATUS "${libdir} is not searched by the dynamic loader: ggx.pc links with -Wl,-rpath,${libdir}")
endif()

# pkg-config finds ggx.pc only in its search path.
if(GGX_PKG_CONFIG AND "$ENV{DESTDIR}" STREQUAL "")
  execute_process(COMMAND "${GGX_PKG_CONFIG}" --variable pc_path pkg-config OUTPUT_VARIABLE pc_path
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  string(REPLACE ":" ";" pc_dirs "${pc_path}")
  if(NOT "${libdir}/pkgconfig" IN_LIST pc_dirs)
    ggx_sh_quote(q "${libdir}/pkgconfig")
    list(APPEND notes "pkg-config does not search ${libdir}/pkgconfig: export PKG_CONFIG_PATH=${q}")
  endif()
endif()
if(NOT CMAKE_INSTALL_PREFIX MATCHES "^[A-Za-z0-9_./:@%+,=-]+$")
  # pkg-config escapes the prefix's spaces, but a shell splits $(...) at every space whatever the escapes
  list(APPEND notes "the prefix holds spaces or quotes: build with eval \"cc prog.c \$(pkg-config --cflags --libs ggx)\" (a shell splits an unquoted \$(...) at every space)")
endif()
foreach(n IN LISTS notes)
  message(STATUS "Note: ${n}")
endforeach()
cmake_policy(POP)
