// Numbers in messages: "%.*g", `digits` significant digits (6 for a value the user typed,
// 3 for a measure), so that every stage writes them alike.
#pragma once

#include <cstdio>
#include <string>

namespace tumble {

inline std::string numberText(double v, int digits = 6) {
    char text[40];
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    return text;
}

}  // namespace tumble
