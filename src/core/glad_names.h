/* Our copy of glad is renamed so that the static library cannot collide with a host that
 * also links glad (the shared library hides it as well). Included before glad/gl.h by
 * gl_loader.c and by every C++ file, so both sides see the same names. --mx glad defines
 * only these two external symbols; tests/packaging/check_symbols.cmake verifies that. */
#pragma once
#define gladLoadGLContext obscura_glad_LoadGLContext
#define gladLoadGLContextUserPtr obscura_glad_LoadGLContextUserPtr
