// The report for people (a table per camera and per phase type, then PASS or FAIL: reasons)
// and for tools (JSON).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "comparison.hpp"

namespace syncap::compare {

// `heading` is the first line, e.g. what was compared with what.
std::string format_summary(const Report& report, const std::string& heading);

// The last line of the summary: "PASS" or "FAIL: <reason>; <reason>".
std::string verdict_line(const Report& report);

nlohmann::ordered_json report_json(const Report& report);

}  // namespace syncap::compare
