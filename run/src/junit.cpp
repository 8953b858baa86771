// JUnit XML as Jenkins, GitLab and GitHub read it: testsuites > testsuite >
// testcase, a failure element per failed case, counts on the suite.
#include "fireswarm/run/junit.hpp"

#include <string>

#include "fireswarm/common/atomic_file.hpp"
#include "xml_text.hpp"

namespace fireswarm::run {
namespace {

using internal::FixedNumber;
using internal::ShortNumber;
using internal::XmlEscape;
using internal::XmlPlace;

// The test case a run without expectations reports: it finished.
constexpr const char* kRunsCaseName = "scenario_runs";
// Wall-clock seconds to the millisecond, as JUnit's time attributes usually are.
constexpr int kTimeDecimals = 3;

// "value 12.3, limit 10" and, when there is one, ": <detail>".
std::string FailureMessage(const ExpectOutcome& outcome) {
  std::string message = outcome.name + ": value " + ShortNumber(outcome.value) + ", limit " +
                        ShortNumber(outcome.limit);
  if (!outcome.detail.empty()) message += ": " + outcome.detail;
  return message;
}

void AppendCase(std::string& xml, const std::string& classname, const ExpectOutcome& outcome) {
  xml += "    <testcase classname=\"" + XmlEscape(classname) + "\" name=\"" +
         XmlEscape(outcome.name) + "\" time=\"0\">\n";
  const std::string value_and_limit =
      "value: " + ShortNumber(outcome.value) + "\nlimit: " + ShortNumber(outcome.limit) + "\n";
  if (outcome.passed) {
    xml += "      <system-out>" + XmlEscape(value_and_limit, XmlPlace::kText) + "</system-out>\n";
  } else {
    xml += "      <failure message=\"" + XmlEscape(FailureMessage(outcome)) +
           "\" type=\"expectation\">" +
           XmlEscape(value_and_limit + (outcome.detail.empty() ? "" : outcome.detail + "\n"),
                     XmlPlace::kText) +
           "</failure>\n";
  }
  xml += "    </testcase>\n";
}

}  // namespace

std::string JunitXml(const Report& report) {
  const std::string classname = "fireswarm.run." + report.scenario;
  std::size_t failures = 0;
  for (const ExpectOutcome& outcome : report.expect) {
    if (!outcome.passed) ++failures;
  }
  const std::size_t tests = report.expect.empty() ? 1 : report.expect.size();
  const std::string counts = "tests=\"" + std::to_string(tests) + "\" failures=\"" +
                             std::to_string(failures) + "\" errors=\"0\" time=\"" +
                             FixedNumber(report.wall_seconds, kTimeDecimals) + "\"";

  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += "<testsuites name=\"fireswarm run\" " + counts + ">\n";
  xml += "  <testsuite name=\"" + XmlEscape(report.scenario) + "\" " + counts + " skipped=\"0\">\n";
  xml += "    <properties>\n";
  xml += "      <property name=\"seed\" value=\"" + std::to_string(report.seed) + "\"/>\n";
  xml +=
      "      <property name=\"sim_seconds\" value=\"" + ShortNumber(report.sim_seconds) + "\"/>\n";
  xml += "      <property name=\"coverage\" value=\"" + ShortNumber(report.coverage) + "\"/>\n";
  xml += "    </properties>\n";
  if (report.expect.empty()) {
    xml += "    <testcase classname=\"" + XmlEscape(classname) + "\" name=\"" + kRunsCaseName +
           "\" time=\"" + FixedNumber(report.wall_seconds, kTimeDecimals) + "\"/>\n";
  }
  for (const ExpectOutcome& outcome : report.expect) AppendCase(xml, classname, outcome);
  xml += "  </testsuite>\n";
  xml += "</testsuites>\n";
  return xml;
}

void WriteJunit(const Report& report, const std::filesystem::path& path) {
  common::WriteFileAtomically(path, JunitXml(report));
}

}  // namespace fireswarm::run
