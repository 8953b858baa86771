// The run's JUnit file: one test case per expectation, counts that match, failure
// messages with the value and the limit, and every name escaped.
#include "fireswarm/run/junit.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "mini_xml.hpp"

namespace fireswarm::run {
namespace {

namespace fs = std::filesystem;
using test::ParseXml;
using test::XmlDocument;
using test::XmlElement;
using ::testing::HasSubstr;
using ::testing::Not;

ExpectOutcome Outcome(const std::string& name, double value, double limit, bool passed,
                      const std::string& detail = "") {
  ExpectOutcome outcome;
  outcome.name = name;
  outcome.value = value;
  outcome.limit = limit;
  outcome.passed = passed;
  outcome.detail = detail;
  return outcome;
}

Report TestReport() {
  Report report;
  report.scenario = "demo";
  report.seed = 42;
  report.wall_seconds = 12.3456;
  report.sim_seconds = 1'500.0;
  report.coverage = 0.96;
  report.expect = {
      Outcome("all_fires_confirmed_within_s", 734.5, 1'200.0, true),
      Outcome("max_fused_error_m", 17.25, 15.0, false,
              "fire 2 (46.35225, -74.394134) is 17.25 m off"),
      Outcome("min_coverage", 0.96, 0.95, true),
  };
  return report;
}

XmlDocument ParsedJunit(const std::string& xml) {
  XmlDocument doc = ParseXml(xml);
  EXPECT_EQ(doc.error, "") << xml;
  return doc;
}

TEST(Junit, OneTestCasePerExpectationWithMatchingCounts) {
  const std::string xml = JunitXml(TestReport());
  EXPECT_THAT(xml, testing::StartsWith("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"));
  const XmlDocument doc = ParsedJunit(xml);
  ASSERT_EQ(doc.Find("testsuites").size(), 1U);
  const auto suites = doc.Find("testsuite");
  ASSERT_EQ(suites.size(), 1U);
  const XmlElement& suite = *suites[0];
  EXPECT_EQ(suite.Attribute("name"), "demo");
  EXPECT_EQ(suite.Attribute("tests"), "3");
  EXPECT_EQ(suite.Attribute("failures"), "1");
  EXPECT_EQ(suite.Attribute("errors"), "0");
  EXPECT_EQ(suite.Attribute("time"), "12.346");
  EXPECT_EQ(doc.Find("testsuites")[0]->Attribute("tests"), "3");
  EXPECT_EQ(doc.Find("testsuites")[0]->Attribute("failures"), "1");
  const auto cases = doc.Find("testcase");
  ASSERT_EQ(cases.size(), 3U);
  EXPECT_EQ(cases[0]->Attribute("name"), "all_fires_confirmed_within_s");
  EXPECT_EQ(cases[1]->Attribute("name"), "max_fused_error_m");
  EXPECT_EQ(cases[2]->Attribute("name"), "min_coverage");
  for (const XmlElement* test_case : cases) {
    EXPECT_EQ(test_case->Attribute("classname"), "fireswarm.run.demo");
    EXPECT_EQ(*test_case->parent, static_cast<std::size_t>(&suite - doc.elements.data()));
  }
  // Properties record what reproduces the run.
  std::map<std::string, std::string> properties;
  for (const XmlElement* property : doc.Find("property")) {
    properties[property->Attribute("name")] = property->Attribute("value");
  }
  EXPECT_EQ(properties["seed"], "42");
  EXPECT_EQ(properties["coverage"], "0.96");
}

TEST(Junit, FailureCarriesValueLimitAndDetail) {
  const XmlDocument doc = ParsedJunit(JunitXml(TestReport()));
  const auto failures = doc.Find("failure");
  ASSERT_EQ(failures.size(), 1U);
  const XmlElement& failure = *failures[0];
  EXPECT_EQ(doc.elements[*failure.parent].Attribute("name"), "max_fused_error_m");
  EXPECT_EQ(failure.Attribute("message"),
            "max_fused_error_m: value 17.25, limit 15: fire 2 (46.35225, -74.394134) is 17.25 m "
            "off");
  EXPECT_THAT(failure.text, HasSubstr("value: 17.25\n"));
  EXPECT_THAT(failure.text, HasSubstr("limit: 15\n"));
  EXPECT_THAT(failure.text, HasSubstr("is 17.25 m off"));
  // Passed cases show their numbers too, and no failure.
  const auto outputs = doc.Find("system-out");
  ASSERT_EQ(outputs.size(), 2U);
  EXPECT_EQ(outputs[0]->text, "value: 734.5\nlimit: 1200\n");
}

TEST(Junit, NoExpectationsIsOnePassingScenarioRunsCase) {
  Report report = TestReport();
  report.expect.clear();
  const XmlDocument doc = ParsedJunit(JunitXml(report));
  const auto cases = doc.Find("testcase");
  ASSERT_EQ(cases.size(), 1U);
  EXPECT_EQ(cases[0]->Attribute("name"), "scenario_runs");
  EXPECT_EQ(cases[0]->Attribute("classname"), "fireswarm.run.demo");
  EXPECT_TRUE(doc.Find("failure").empty());
  EXPECT_EQ(doc.Find("testsuite")[0]->Attribute("tests"), "1");
  EXPECT_EQ(doc.Find("testsuite")[0]->Attribute("failures"), "0");
}

TEST(Junit, EscapesNamesAndMessages) {
  Report report = TestReport();
  report.scenario = "a<b & \"c\"";
  report.expect[1].detail = "x < y && 'z' > \"w\"\nsecond line\x01";
  const std::string xml = JunitXml(report);
  EXPECT_THAT(xml, Not(HasSubstr("a<b")));
  const XmlDocument doc = ParsedJunit(xml);
  EXPECT_EQ(doc.Find("testsuite")[0]->Attribute("name"), "a<b & \"c\"");
  EXPECT_EQ(doc.Find("testcase")[0]->Attribute("classname"), "fireswarm.run.a<b & \"c\"");
  // The newline survives in the attribute (as &#10;); the control character, which
  // XML cannot hold, does not.
  EXPECT_THAT(doc.Find("failure")[0]->Attribute("message"),
              HasSubstr("x < y && 'z' > \"w\"\nsecond line?"));
}

TEST(Junit, IsDeterministic) {
  EXPECT_EQ(JunitXml(TestReport()), JunitXml(TestReport()));
}

TEST(Junit, WriteJunitWritesTheSameDocument) {
  const fs::path dir = fs::temp_directory_path() / ("junit_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / "run.xml";
  WriteJunit(TestReport(), path);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), JunitXml(TestReport()));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fireswarm::run
