/* The C ABI tests' checks: CHECK counts a failure (with gyro's last error) and goes on, so
 * one run reports every broken expectation; STATIC_ASSERT pins struct layouts at compile
 * time (C99 has no _Static_assert and -pedantic rejects the C11 one: a false condition gives
 * an array of size -1). */
#ifndef GYRO_TESTS_CAPI_CHECK_H
#define GYRO_TESTS_CAPI_CHECK_H

#include "gyro.h"

#include <stdio.h>

static int failures = 0;

#define CHECK(cond)                                                                            \
  do {                                                                                         \
    if (!(cond)) {                                                                             \
      fprintf(stderr, "%s:%d: CHECK failed: %s (last error: %s)\n", __FILE__, __LINE__, #cond, \
              gyro_last_error());                                                              \
      ++failures;                                                                              \
    }                                                                                          \
  } while (0)

#define STATIC_ASSERT(cond, name) typedef char static_assert_##name[(cond) ? 1 : -1]

#endif
