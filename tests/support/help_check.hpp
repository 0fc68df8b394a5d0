// A program's --help stays complete (issue 16): every option, its meaning and default, the exit
// statuses. The tests list what must stand in it.
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

namespace syncap::test {

inline void expect_help_mentions(const std::string& help,
                                 std::initializer_list<const char*> texts) {
  for (const char* text : texts)
    EXPECT_NE(help.find(text), std::string::npos) << text << " missing from:\n" << help;
}

}  // namespace syncap::test
