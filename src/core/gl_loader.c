/* Compiles the generated glad (--mx) loader into the library under renamed symbols. */
#include "core/glad_names.h"
#include "gl.c"
