// Host state of the GL extensions whose state the state guard saves and resets
// (src/core/state_guard.cpp), for tests/gl/test_state.cpp.
#pragma once
#include <string>

namespace obscura::test {

//! The extensions of that list the current context has, by name ("none"): llvmpipe has
//! none, so the log of a run on a GPU (benchmarks/gpu/run.sh tests) says which of the
//! guard's paths it tested.
std::string guardedExtensionsPresent();

//! Sets each of those extensions' state that the context has to a value that would change
//! what our draws write, were it not reset.
void setUnusualExtensionState();

} // namespace obscura::test
