#pragma once
// `verify --html` (run/html_report.h): the page written, the outcome printed.

#include <string>

#include "stitchsim/run/html_report.h"

namespace stitchsim::app {

using run::HtmlInputs;
using run::HtmlLimits;

/// Writes the page whole or not at all; exit code (errors printed).
int WriteHtmlReport(const std::string& path, const HtmlInputs& in);

}  // namespace stitchsim::app
