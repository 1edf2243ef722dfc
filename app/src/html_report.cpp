#include "html_report.h"

#include "commands.h"

namespace stitchsim::app {

int WriteHtmlReport(const std::string& path, const HtmlInputs& in) {
  return PrintRunOutcome(DiagnosticSink{}, run::WriteHtmlReportFile(path, in));
}

}  // namespace stitchsim::app
