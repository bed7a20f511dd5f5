#pragma once
// The independent programs tests check outputs with (the glTF validator, assimp, mido,
// fluidsynth, ffmpeg, Blender, jackd) come with the test command (.ci/setup). Where one
// is missing, a test skips on a developer's machine but fails in CI (CI=true), so that a
// missing install step can never pass as green.

#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

/// True when the tests run in CI (the environment variable CI is "true"). Global, so that
/// tests with a helper of their own named `ontogen` can include this too.
inline bool ontogenTestsRunInCi() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string(ci) == "true";
}

/// Skips the test (fails it in CI) unless `available`; `message` is streamed, as in
/// ONTOGEN_REQUIRE_CHECKER(haveMido(), "python3-mido is missing").
#define ONTOGEN_REQUIRE_CHECKER(available, message)                                   \
  do {                                                                                \
    if (!(available)) {                                                               \
      if (::ontogenTestsRunInCi()) FAIL() << message << " (in CI)"; \
      GTEST_SKIP() << message;                                                        \
    }                                                                                 \
  } while (false)
