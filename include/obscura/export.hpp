#pragma once
// Symbol visibility. The library is compiled with hidden visibility; only what is marked
// OBSCURA_API is part of the ABI. The GL loader inside is never exported (see context.hpp).
#if defined(_WIN32)
#  if defined(OBSCURA_SHARED) && defined(OBSCURA_BUILDING)
#    define OBSCURA_API __declspec(dllexport)
#  elif defined(OBSCURA_SHARED)
#    define OBSCURA_API __declspec(dllimport)
#  else
#    define OBSCURA_API
#  endif
#else
#  define OBSCURA_API __attribute__((visibility("default")))
#endif
