#pragma once
// HBOS_TEST_UNDER_ASAN is defined when AddressSanitizer instruments this build (GCC defines
// __SANITIZE_ADDRESS__, Clang answers __has_feature). Tests of address-space limits cannot run
// there: ASan reserves terabytes of shadow address space at start-up.

#if defined(__SANITIZE_ADDRESS__)
#define HBOS_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HBOS_TEST_UNDER_ASAN 1
#endif
#endif
