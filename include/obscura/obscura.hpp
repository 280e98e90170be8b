#pragma once
// Obscura: real-time global-illumination approximations and visibility queries on the
// host's OpenGL 4.5 context. One header per module; this one includes them all.
#include "obscura/ambient_occlusion.hpp"
#include "obscura/camera.hpp"
#include "obscura/compose.hpp"
#include "obscura/context.hpp"
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/indirect_light.hpp"
#include "obscura/metrics.hpp"
#include "obscura/profiler.hpp"
#include "obscura/scene.hpp"
#include "obscura/screen_visibility.hpp"
#include "obscura/shadow_maps.hpp"
#include "obscura/texture.hpp"
#include "obscura/version.hpp"
#include "obscura/voxelizer.hpp"
