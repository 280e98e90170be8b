#pragma once
#include "obscura/export.hpp"

#include <stdexcept>
#include <string>

namespace obscura {

enum class ErrorCode {
    InvalidArgument,    //!< a value outside its documented range, a NaN, a wrong size or format
    UnsupportedFeature, //!< the GL context lacks a version, function, limit or format we need
    ShaderCompile,      //!< a shader failed to compile or link (message has file:line)
    OutOfMemory,        //!< GL_OUT_OF_MEMORY while allocating a resource
    InvalidState,       //!< the call is not allowed in the current GL state (e.g. active transform feedback)
    Io,                 //!< a file could not be read or written
    Parse,              //!< a scene or settings file is malformed
};

OBSCURA_API const char* toString(ErrorCode code) noexcept;

//! Every failure of Obscura is reported as this exception. The message says what was
//! given and what is accepted. When it is thrown, no GL error is left pending and no GL
//! object created by the failing call survives.
class OBSCURA_API Error : public std::runtime_error {
public:
    Error(ErrorCode code, const std::string& message);
    ErrorCode code() const noexcept { return code_; }
    //! The message alone, without what()'s "obscura: <code>: " prefix (to wrap it in context).
    const std::string& message() const noexcept { return message_; }

private:
    ErrorCode code_;
    std::string message_;
};

} // namespace obscura
