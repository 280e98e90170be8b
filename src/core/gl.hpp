#pragma once
// The only way Obscura code reaches GL: through the per-context function table
// (GladGLContext) of our private, renamed glad. Never include another GL header.
#include "core/glad_names.h"
#include <glad/gl.h>
