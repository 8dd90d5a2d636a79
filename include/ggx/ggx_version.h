/*
 * libggx version. SPDX-License-Identifier: MIT
 *
 * The version is written here only: the build takes it from these three lines (CMakeLists.txt), for the shared
 * library's SONAME, ggx.pc, the CMake package and the Python package. Included by ggx.h.
 *
 * GGX_VERSION_MAJOR, GGX_VERSION_MINOR, GGX_VERSION_PATCH: integer constants, usable in #if.
 * GGX_VERSION_STRING: the string literal "MAJOR.MINOR.PATCH" (decimal, no leading zeros), e.g. "0.1.0".
 * These describe the headers a program is compiled with; ggx_version() describes the library it runs with.
 */
#ifndef GGX_GGX_VERSION_H
#define GGX_GGX_VERSION_H

#define GGX_VERSION_MAJOR 0
#define GGX_VERSION_MINOR 1
#define GGX_VERSION_PATCH 0

#define GGX_VERSION_STR2_(a, b, c) #a "." #b "." #c
#define GGX_VERSION_STR_(a, b, c) GGX_VERSION_STR2_(a, b, c)
#define GGX_VERSION_STRING GGX_VERSION_STR_(GGX_VERSION_MAJOR, GGX_VERSION_MINOR, GGX_VERSION_PATCH)

#ifdef __cplusplus
extern "C" {
#endif

/* The version of the libggx a program runs with, "MAJOR.MINOR.PATCH" (GGX_VERSION_STRING of the headers the library
 * was built from): a static string, never NULL, the same at every call. A program that differs from the
 * GGX_VERSION_STRING it was compiled with runs with another library than its headers describe. */
const char *ggx_version(void);

#ifdef __cplusplus
}
#endif

#endif
