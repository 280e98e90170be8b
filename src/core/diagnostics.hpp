#pragma once
// Obscura's own reports of likely host mistakes (obscura::Diagnostic, context.hpp).
#include "obscura/context.hpp"

#include <string>

namespace obscura::detail {

struct ContextImpl;

//! Whether a report would reach anyone: ContextDesc::debugOutput or strictChecks is set, or
//! the host enabled GL_DEBUG_OUTPUT (queried: call before a StateScope changes it). Checks
//! that cost a stall run only then.
bool diagnosticsDelivered(ContextImpl& ctx);

//! Sends `text` as `what` to ContextDesc::debugOutput, else into the GL debug log; with
//! ContextDesc::strictChecks throws Error{InvalidArgument} with it instead.
void reportDiagnostic(ContextImpl& ctx, Diagnostic what, const std::string& text);

} // namespace obscura::detail
