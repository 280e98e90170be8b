// Screen-space visibility: the texture units its GLSL functions read, shared by the modules
// that include shaders/visibility/screen_march.glsl and their host code.
#ifndef OBSCURA_VISIBILITY_BINDINGS_H
#define OBSCURA_VISIBILITY_BINDINGS_H

#define VIS_DEPTH_UNIT 5  // the G-buffer's hardware depth (sampler2D, texelFetch)
#define VIS_NORMAL_UNIT 6 // the G-buffer's view-space geometric normal (alpha 1 on geometry)

#endif
