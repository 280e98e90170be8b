#include "obscura/error.hpp"

namespace obscura {

const char* toString(ErrorCode code) noexcept {
    switch (code) {
    case ErrorCode::InvalidArgument: return "invalid argument";
    case ErrorCode::UnsupportedFeature: return "unsupported feature";
    case ErrorCode::ShaderCompile: return "shader compile error";
    case ErrorCode::OutOfMemory: return "out of memory";
    case ErrorCode::InvalidState: return "invalid state";
    case ErrorCode::Io: return "I/O error";
    case ErrorCode::Parse: return "parse error";
    }
    return "unknown error";
}

Error::Error(ErrorCode code, const std::string& message)
    : std::runtime_error(std::string("obscura: ") + toString(code) + ": " + message), code_(code), message_(message) {}

} // namespace obscura
