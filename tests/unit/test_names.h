/* Shared by the unit tests of the enum name tables (TLOD_*_NAMES in the
 * public headers): DEFINE_NAMES_CHECK(prefix, type, TABLE, num) defines
 * static void prefix##_names_check(int rows), which checks that the table
 * has `rows` entries, every entry round-trips through prefix##_name() and
 * prefix##_from_name(), the value num has no name, and unknown names (or a
 * NULL name or out) are refused with *out left alone. */
#ifndef TLOD_TEST_NAMES_H
#define TLOD_TEST_NAMES_H

#include "test.h"

static const char* const test_bad_names[] = {"", "bogus", "Phong", "FLAT", "HYBRID", " time", "default", "quads"};

#define TEST_NAME_ROW(value, text) {value, text},
#define DEFINE_NAMES_CHECK(prefix, type, TABLE, num)                                                                   \
  static void prefix##_names_check(int expected_rows) {                                                                \
    static const struct {                                                                                              \
      type value;                                                                                                      \
      const char* name;                                                                                                \
    } rows[] = {TABLE(TEST_NAME_ROW)};                                                                                 \
    CHECK((int)(sizeof rows / sizeof rows[0]) == expected_rows);                                                       \
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; r++) {                                                        \
      type got = (type)(num);                                                                                          \
      const char* name = prefix##_name(rows[r].value);                                                                 \
      CHECK_MSG(name&& strcmp(name, rows[r].name) == 0, "%s", rows[r].name);                                           \
      CHECK_MSG(prefix##_from_name(rows[r].name, &got) && got == rows[r].value, "%s", rows[r].name);                   \
    }                                                                                                                  \
    CHECK(prefix##_name((type)(num)) == NULL);                                                                         \
    type untouched = (type)(num);                                                                                      \
    for (size_t b = 0; b < sizeof test_bad_names / sizeof test_bad_names[0]; b++)                                      \
      CHECK_MSG(!prefix##_from_name(test_bad_names[b], &untouched) && untouched == (type)(num), "'%s'",                \
                test_bad_names[b]);                                                                                    \
    CHECK(!prefix##_from_name(NULL, &untouched) && !prefix##_from_name(rows[0].name, NULL));                           \
  }

#endif
