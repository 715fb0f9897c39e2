#pragma once
// Whether this test executable is built with AddressSanitizer (the sanitizer stage of
// scripts/test.sh). A few tests that take minutes under the sanitizers run the same checks on
// fewer or smaller cases there; the full sets run in the Release build. Each test that uses this
// says which cases it cuts and why (docs/development.md lists them).

namespace freeform::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool underSanitizers = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool underSanitizers = true;
#else
inline constexpr bool underSanitizers = false;
#endif
#else
inline constexpr bool underSanitizers = false;
#endif

} // namespace freeform::test
