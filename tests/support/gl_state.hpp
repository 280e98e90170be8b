#pragma once
// An independent snapshot of GL state, read through the test's own loader. It covers every
// item listed in include/obscura/context.hpp, on more units than Obscura touches, plus state
// Obscura promises never to change (clear values, other viewport indices, hints, ...).
#include <map>
#include <string>
#include <vector>

namespace obscura::test {

using GlState = std::map<std::string, std::vector<double>>;

GlState captureGlState();
//! "name: before -> after" lines for every differing entry (empty when equal).
std::vector<std::string> diffGlState(const GlState& before, const GlState& after);

} // namespace obscura::test
