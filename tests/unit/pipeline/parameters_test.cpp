// The parameter table (crestline/parameters.h): ranges, the automatic mode,
// and the stage each parameter dirties in Pipeline::set_options.
#include "crestline/parameters.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <string>

#include "analytic_meshes.h"
#include "crestline/mesh/repair.h"

using namespace crestline;

namespace {

/// A value of p inside its range and different from the default.
ParameterValue another_value(const Parameter& p) {
  ParameterValue v = p.get(Settings{});
  switch (p.kind) {
    case ParameterKind::Boolean:
      v.number = 1 - v.number;
      break;
    case ParameterKind::Choice:
      v.choice = v.choice == p.choices[0] ? p.choices[1] : p.choices[0];
      break;
    default:
      if (v.automatic)
        v = {false, p.min, ""};
      else
        v.number = v.number == p.min ? p.min + 1 : p.min;
  }
  return v;
}

}  // namespace

TEST_CASE("the table: unique keys and flags, defaults inside their ranges", "[parameters]") {
  std::set<std::string> keys, flags;
  for (const Parameter& p : parameters()) {
    CAPTURE(p.key);
    CHECK(keys.insert(p.key).second);
    CHECK(flags.insert(p.flag).second);
    CHECK(std::string(p.flag).rfind("--", 0) == 0);
    CHECK(find_parameter_by_key(p.key) == &p);
    CHECK_NOTHROW(check_parameter(p, p.get(Settings{}), p.key));
    // Every value read back is the value set.
    Settings s;
    const ParameterValue v = another_value(p);
    p.set(s, v);
    CHECK(p.get(s) == v);
  }
  CHECK(find_parameter_by_key("noSuchKey") == nullptr);
}

TEST_CASE("parsing: ranges, whole numbers, auto, and no nan", "[parameters]") {
  const Parameter& steps = *find_parameter_by_key("smoothingSteps");
  CHECK(parse_parameter(steps, "0").number == 0);
  CHECK(parse_parameter(steps, "50").number == 50);
  for (const char* bad : {"51", "-1", "1e9", "2.5", "nan", "inf", "auto", "", " 3", "3 ", "0x3", "three"}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(parse_parameter(steps, bad), UsageError);
  }
  CHECK_THROWS_WITH(parse_parameter(steps, "1000000000"),
                    "--smoothing-steps must be a whole number from 0 to 50; got \"1000000000\".");

  const Parameter& threshold = *find_parameter_by_key("threshold");
  CHECK(parse_parameter(threshold, "auto").automatic);
  CHECK(parse_parameter(threshold, "inf").number == INFINITY);
  CHECK(parse_parameter(threshold, "0.5").number == 0.5);
  CHECK_THROWS_WITH(parse_parameter(threshold, "nan"),
                    "--threshold must be auto or a number from 0 to inf; got \"nan\".");
  CHECK_THROWS_AS(parse_parameter(threshold, "-1"), UsageError);
  // A value from JavaScript is checked the same way, named by its key.
  CHECK_THROWS_WITH(check_parameter(threshold, {false, std::nan(""), ""}, "threshold"),
                    "threshold must be auto or a number from 0 to inf; got nan.");

  // A long word is not repeated whole.
  const std::string digits(309, '9');
  try {
    parse_parameter(*find_parameter_by_key("hausdorffBound"), digits);
    FAIL("accepted a 309-digit bound");
  } catch (const UsageError& e) {
    CHECK(std::string(e.what()).size() < 120);
  }
  CHECK_THROWS_WITH(parse_parameter(*find_parameter_by_key("view"), "sideways"),
                    "--view must be one of front, back, left, right, top, bottom; got \"sideways\".");
}

TEST_CASE("set_options re-runs from the stage the table names for each parameter", "[parameters][pipeline]") {
  testing::GridOptions grid;
  grid.nu = grid.nv = 12;
  const TriangleSoup soup =
      testing::height_field([](double x, double y) { return 0.1 * std::cos(5 * x) * std::cos(4 * y); }, 2, 2, grid);
  Pipeline pipeline(repair_mesh(soup).mesh);
  pipeline.run();
  for (const Parameter& p : parameters()) {
    CAPTURE(p.key);
    Settings changed;
    p.set(changed, another_value(p));
    CHECK(first_changed_stage(PipelineOptions{}, changed.pipeline) == p.stage);
    pipeline.set_options(changed.pipeline);
    std::vector<Stage> ran;
    pipeline.run([&](Stage s, double fraction) {
      if (fraction == 0) ran.push_back(s);
      return true;
    });
    CHECK((ran.empty() ? Stage::Count : ran.front()) == p.stage);
    pipeline.set_options(PipelineOptions{});
    pipeline.run();
  }
  PipelineOptions weighted;
  weighted.smoothing.vertex_weights.assign(pipeline.input_mesh().positions.size(), 0.5);
  CHECK(first_changed_stage(PipelineOptions{}, weighted) == Stage::Smoothing);
  PipelineOptions averaged;
  averaged.averaging.rings = 1;
  CHECK(first_changed_stage(PipelineOptions{}, averaged) == Stage::Curvature);
}
