# What the test suite needs besides the compiler, looked for by CMakeLists.txt when the tests are wanted: sets
# GGX_TEST_DEPS_FOUND, and GGX_TEST_MISSING to the missing programs with their Debian packages. Also leaves
# CMOCKA_INCLUDE_DIRS and CMOCKA_LIBRARIES for tests/CMakeLists.txt. Needs PkgConfig looked for (find_package), and
# GGX_BUILD_TOOL and GGX_BUILD_PYTHON resolved: their tests need more.
set(ggx_missing "")
set(ggx_packages "")
macro(ggx_test_missing what package)
  list(APPEND ggx_missing "${what}")
  list(APPEND ggx_packages "${package}")
endmacro()

# pkg-config: the install test builds a program with `pkg-config --cflags --libs ggx`.
if(NOT PKG_CONFIG_FOUND)
  ggx_test_missing(pkg-config pkg-config)
else()
  pkg_check_modules(CMOCKA QUIET cmocka)
endif()
# cmocka: the unit tests are cmocka programs.
if(NOT CMOCKA_FOUND)
  find_path(CMOCKA_INCLUDE_DIRS cmocka.h)
  find_library(CMOCKA_LIBRARIES cmocka)
  if(NOT CMOCKA_INCLUDE_DIRS OR NOT CMOCKA_LIBRARIES)
    ggx_test_missing(cmocka libcmocka-dev)
  endif()
endif()
# make: the install test runs `make install PREFIX=...`.
find_program(GGX_MAKE NAMES make gmake)
if(NOT GGX_MAKE)
  ggx_test_missing(make make)
endif()
mark_as_advanced(GGX_MAKE)
# The command's tests read its PDF figures' pages (pdfinfo, pdftotext), validate its SVG figures (xmllint) and render
# its man page (groff).
if(GGX_BUILD_TOOL)
  find_program(GGX_XMLLINT xmllint)
  find_program(GGX_GROFF groff)
  find_program(GGX_PDFINFO pdfinfo)
  mark_as_advanced(GGX_XMLLINT GGX_GROFF GGX_PDFINFO)
  if(NOT GGX_PDFINFO)
    ggx_test_missing(pdfinfo poppler-utils)
  endif()
  if(NOT GGX_XMLLINT)
    ggx_test_missing(xmllint libxml2-utils)
  endif()
  if(NOT GGX_GROFF)
    ggx_test_missing(groff groff-base)
  endif()
endif()
# The Python package's tests run with pytest and draw the example's figure with matplotlib.
if(GGX_BUILD_PYTHON)
  execute_process(COMMAND ${GGX_PYTHON_EXE} -c "import pytest, matplotlib" RESULT_VARIABLE ggx_rc
                  OUTPUT_QUIET ERROR_QUIET)
  if(NOT ggx_rc EQUAL 0)
    ggx_test_missing("pytest and matplotlib for ${GGX_PYTHON_EXE}" "python3-pytest python3-matplotlib")
  endif()
endif()

if(ggx_missing)
  set(GGX_TEST_DEPS_FOUND FALSE)
  string(REPLACE ";" ", " ggx_missing "${ggx_missing}")
  string(REPLACE ";" " " ggx_packages "${ggx_packages}")
  set(GGX_TEST_MISSING "${ggx_missing} not found: apt-get install ${ggx_packages}")
else()
  set(GGX_TEST_DEPS_FOUND TRUE)
  set(GGX_TEST_MISSING "")
endif()
