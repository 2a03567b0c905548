#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "util/params.h"
#include "util/registry.h"

namespace radkit {
namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(Params, ParsesNumbersTriplesAndNames) {
  Params p = Params::parse(" omega = 1.5, colour=0.1 0.2 0.3, mode=fast ,");
  EXPECT_EQ(p.number("omega", 0.0), 1.5);
  EXPECT_EQ(p.rgb("colour", {}), (Vec3{0.1, 0.2, 0.3}));
  EXPECT_EQ(p.text("mode", "slow"), "fast");
  EXPECT_EQ(p.number("missing", 7.0), 7.0);
  EXPECT_NO_THROW(p.rejectUnused("x"));
  EXPECT_TRUE(Params::parse("").empty());
  EXPECT_EQ(Params({{"omega", 0.7}}).number("omega", 0.0), 0.7);
}

TEST(Params, RefusesBadTextNamingTheKey) {
  EXPECT_NE(errorOf([] { Params::parse("omega"); }).find("\"omega\" is not key=value"),
            std::string::npos);
  EXPECT_NE(errorOf([] { Params::parse("=1"); }).find("has no key"), std::string::npos);
  EXPECT_NE(errorOf([] { Params::parse("omega="); }).find("\"omega\" has no value"),
            std::string::npos);
  EXPECT_NE(errorOf([] { Params::parse("a=1, a=2"); }).find("\"a\" is given twice"),
            std::string::npos);
  EXPECT_NE(errorOf([] { Params::parse("a=1 x"); }).find("mixes numbers and names"),
            std::string::npos);
  for (const char* bad : {"omega=fast", "omega=1.5x", "omega=nan", "omega=1 2"}) {
    Params p = Params::parse(bad);
    EXPECT_NE(errorOf([&] { p.number("omega", 0.0); }).find("must be one finite number"),
              std::string::npos)
        << bad;
  }
}

TEST(Params, RangesAndWholeNumbers) {
  Params p({{"g", 1.0}, {"n", 2.5}, {"k", 3}});
  EXPECT_NE(errorOf([&] { p.number("g", 0, -1, 1, true, true); }).find("1 is outside (-1, 1)"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { p.integer("n", 1, 1, 10); }).find("not a whole number in [1, 10]"),
            std::string::npos);
  EXPECT_EQ(p.integer("k", 1, 1, 10), 3);
  EXPECT_NE(errorOf([&] { p.integer("k", 1, 4, 10); }).find("not a whole number"),
            std::string::npos);
  EXPECT_EQ(p.integer("absent", 5, 1, 10), 5);
}

TEST(Params, RejectUnusedNamesUnknownAndKnownKeys) {
  Params p = Params::parse("omega=1, omgea=2");
  p.number("omega", 0.0);
  p.number("power_iterations", 30);
  const std::string e = errorOf([&] { p.rejectUnused("sor"); });
  EXPECT_NE(e.find("gives \"omgea\", which sor does not use"), std::string::npos) << e;
  EXPECT_NE(e.find("Fix: sor reads omega, power_iterations"), std::string::npos) << e;
  Params none = Params::parse("x=1");
  EXPECT_NE(errorOf([&] { none.rejectUnused("jacobi"); }).find("jacobi has no parameters"),
            std::string::npos);
}

struct Shape {
  virtual ~Shape() = default;
  double size = 0;
};

std::unique_ptr<Shape> makeSquare(Params& p, double scale) {
  auto s = std::make_unique<Shape>();
  s->size = scale * p.number("side", 1.0, 0.0, 10.0, true);
  return s;
}
std::unique_ptr<Shape> makePoint(Params&, double) { return std::make_unique<Shape>(); }

TEST(Registry, MakesByNameAndNamesTheKindInErrors) {
  const Registry<Shape, double> shapes("shape",
                                       {{"square", makeSquare, "a square; side (1)", "side=2"},
                                        {"point", makePoint, "a point; no parameters", ""}});
  EXPECT_EQ(shapes.names(), (std::vector<std::string>{"square", "point"}));
  EXPECT_EQ(shapes.make("square", Params::parse("side=2"), 3.0)->size, 6.0);
  EXPECT_EQ(shapes.find("circle"), nullptr);
  const std::string unknown = errorOf([&] { shapes.make("circle", {}, 1.0); });
  EXPECT_EQ(unknown, "unknown shape \"circle\". Fix: use one of square, point");
  EXPECT_THROW(shapes.make("circle", {}, 1.0), UnknownNameError);
  const std::string range = errorOf([&] { shapes.make("square", Params::parse("side=20"), 1.0); });
  EXPECT_EQ(range.rfind("shape \"square\": \"side\" 20 is outside (0, 10]", 0), 0u) << range;
  const std::string unused = errorOf([&] { shapes.make("point", Params::parse("side=2"), 1.0); });
  EXPECT_EQ(unused,
            "shape \"point\": gives \"side\", which point does not use. Fix: point has "
            "no parameters");
}

}  // namespace
}  // namespace radkit
