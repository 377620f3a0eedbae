// The one JSON reader: the same mistake gets the same InputError (file, full key path, value as
// written, reason) whatever the file type; and the one duplicate-name rule of the libraries.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/base/asset_names.h"
#include "core/base/json_reader.h"

namespace pmsim {
namespace {

using nlohmann::json;

// The InputError f() throws (fails the test when it throws none).
template <class F>
InputError error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", "", "", "");
}

enum class Colour { Red, Green };
const NameTable<Colour> kColours = {{"red", Colour::Red}, {"green", Colour::Green}};

TEST(JsonReader, ReadsTypedValuesAtDotPaths) {
  const json j = json::parse(R"({"front":{"radius_mm":12.5},"n":3,"on":true,"name":"x",
                                 "axis":[0,0,2],"colour":"GREEN"})");
  const JsonReader r(j, "lens.json");
  EXPECT_EQ(r.require<double>("front.radius_mm"), 12.5);
  EXPECT_EQ(r.require<int>("n"), 3);
  EXPECT_TRUE(r.require<bool>("on"));
  EXPECT_EQ(r.require<std::string>("name"), "x");
  EXPECT_EQ(r.require_unit_vector("axis"), (std::array<double, 3>{0, 0, 1}));
  EXPECT_EQ(r.require_enum("colour", kColours), Colour::Green);  // names match in any case
  EXPECT_FALSE(r.optional<double>("back.radius_mm").has_value());
  EXPECT_EQ(r.get_or("missing", 7.0), 7.0);
  EXPECT_EQ(r.object("front").require<double>("radius_mm"), 12.5);
}

TEST(JsonReader, ErrorsNameFileFullKeyPathValueAndReason) {
  const json j = json::parse(R"({"front":{"radius_mm":"big"},"n":1.5,"axis":[0,0,0],
                                 "colour":"blue","t":-1,"grains":[{"w":"a"}],"sub":4})");
  const JsonReader r(j, "f.json");
  struct Case {
    InputError e;
    const char* key;
    const char* value;
    const char* reason;
  };
  const Case cases[] = {
      {error_of([&] { r.require<double>("front.radius_mm"); }), "front.radius_mm", "big",
       "expected a number"},
      {error_of([&] { r.require<int>("n"); }), "n", "1.5", "expected an integer"},
      {error_of([&] { r.require<bool>("n"); }), "n", "1.5", "expected true or false"},
      {error_of([&] { r.require<std::string>("n"); }), "n", "1.5", "expected a string"},
      {error_of([&] { r.require_unit_vector("axis"); }), "axis", "[0,0,0]",
       "a direction cannot be the zero vector"},
      {error_of([&] { r.require_enum("colour", kColours); }), "colour", "blue", "expected one of red|green"},
      {error_of([&] { r.require<double>("t", Range::above(0)); }), "t", "-1", "must be > 0"},
      {error_of([&] { r.require<double>("t", Range::open_closed(0, 5)); }), "t", "-1", "must be in (0, 5]"},
      {error_of([&] { r.require<double>("nothing"); }), "nothing", "", "missing required key"},
      {error_of([&] { r.objects("grains")[0].require<double>("w"); }), "grains[0].w", "a",
       "expected a number"},
      {error_of([&] { r.object("sub"); }), "sub", "4", "expected an object"},
      {error_of([&] {
         r.refuse_unknown_keys({"front", "n", "axis", "colour", "t", "grains"});
       }),
       "sub", "4", "unknown key"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.key);
    EXPECT_EQ(c.e.file, "f.json");
    EXPECT_EQ(c.e.key, c.key);
    EXPECT_EQ(c.e.value, c.value);
    EXPECT_EQ(c.e.reason, c.reason);
  }
}

TEST(JsonReader, UnknownKeysAreWarningsWithTheirFullPath) {
  const json j = json::parse(R"({"render":{"spp":4,"sp":5}})");
  std::vector<std::string> warnings;
  const JsonReader r(j, "s.json", "", &warnings);
  r.object("render").warn_unknown_keys({"spp"});
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "s.json: unknown key 'render.sp' ignored");
}

TEST(AssetNames, ADuplicateNameIsAnErrorNamingBothFiles) {
  AssetNames names("mineral");
  names.add("Quartz", "a/quartz.json");
  names.add("calcite", "a/calcite.json");
  const InputError e = error_of([&] { names.add("QUARTZ", "b/quartz2.json"); });  // any case
  EXPECT_EQ(e.file, "b/quartz2.json");
  EXPECT_EQ(e.key, "name");
  EXPECT_EQ(e.value, "QUARTZ");
  EXPECT_NE(e.reason.find("a/quartz.json"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace pmsim
