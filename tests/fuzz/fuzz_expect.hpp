#pragma once
// What a target checks beyond "no crash": a reader that returns must return what it promises. A broken
// promise aborts, so libFuzzer keeps the input like any other crash.
#include <cstdio>
#include <cstdlib>

namespace imucal::fuzz {

[[noreturn]] inline void broken(const char* what) {
  std::fprintf(stderr, "imucal fuzz: broken promise: %s\n", what);
  std::abort();
}

inline void expect(bool ok, const char* what) {
  if (!ok) broken(what);
}

}  // namespace imucal::fuzz
