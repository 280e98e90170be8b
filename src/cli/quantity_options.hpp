#pragma once
// `--integrator NAME --set key=value` for the reference quantities (obscura reference, bench).
#include "obscura/reference.hpp"

#include <string>
#include <vector>

namespace obscura::cli {

//! Integrator names: ao, obscurance, bent_normal, direct, indirect, shadow, media, ibl.
std::vector<std::string> integratorNames();
//! Builds the quantity from its name and key=value settings; throws Error{Parse} naming an
//! unknown integrator or key and listing the accepted ones.
reference::Quantity parseQuantity(const std::string& integrator, const std::vector<std::string>& sets);

} // namespace obscura::cli
