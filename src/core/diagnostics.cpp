#include "core/diagnostics.hpp"

#include "core/context_impl.hpp"
#include "obscura/error.hpp"

#include <algorithm>

namespace obscura::detail {

bool diagnosticsDelivered(ContextImpl& ctx) {
    return ctx.desc.debugOutput || ctx.desc.strictChecks || ctx.gl.IsEnabled(GL_DEBUG_OUTPUT);
}

void reportDiagnostic(ContextImpl& ctx, Diagnostic what, const std::string& text) {
    if (ctx.desc.strictChecks) throw Error(ErrorCode::InvalidArgument, text + " (ContextDesc::strictChecks)");
    const auto id = static_cast<unsigned>(what);
    if (ctx.desc.debugOutput) {
        // The host's callback may throw; a report must not.
        try {
            ctx.desc.debugOutput({GL_DEBUG_SOURCE_THIRD_PARTY, GL_DEBUG_TYPE_OTHER, id, GL_DEBUG_SEVERITY_MEDIUM, text});
        } catch (...) {
        }
        return;
    }
    // A message longer than GL_MAX_DEBUG_MESSAGE_LENGTH (at least 1, 4096 on Mesa) would be
    // refused with GL_INVALID_VALUE: cut to it.
    GLint longest = 0;
    ctx.gl.GetIntegerv(GL_MAX_DEBUG_MESSAGE_LENGTH, &longest);
    const auto length = static_cast<GLsizei>(std::min<std::size_t>(text.size(), std::size_t(std::max(longest - 1, 0))));
    ctx.gl.DebugMessageInsert(GL_DEBUG_SOURCE_THIRD_PARTY, GL_DEBUG_TYPE_OTHER, id, GL_DEBUG_SEVERITY_MEDIUM, length,
                              text.c_str());
}

} // namespace obscura::detail
