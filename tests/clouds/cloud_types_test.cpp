// Cloud-type profiles (height_profile.hpp), the cloud-type texture and the
// height-gradient table: closed forms at sample heights, exact zeros outside
// [a, d], ranges, the documented column order and the row <-> height and
// type <-> u mappings with their inverses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "clouds/cloud_types.hpp"
#include "clouds/height_gradients.hpp"
#include "clouds/height_profile.hpp"

namespace skybake {
namespace {

// The closed form written out independently of the code under test.
double hermite(double e0, double e1, double x) {
  if (x <= e0) return 0.0;
  if (x >= e1) return 1.0;
  const double t = (x - e0) / (e1 - e0);
  return t * t * (3.0 - 2.0 * t);
}

TEST(HeightProfile, SmoothstepEndsAndMidpoint) {
  EXPECT_EQ(smoothstep(0.2, 0.4, 0.1), 0.0);
  EXPECT_EQ(smoothstep(0.2, 0.4, 0.2), 0.0);
  EXPECT_EQ(smoothstep(0.2, 0.4, 0.4), 1.0);
  EXPECT_EQ(smoothstep(0.2, 0.4, 0.9), 1.0);
  EXPECT_NEAR(smoothstep(0.2, 0.4, 0.3), 0.5, 1e-15);       // symmetric about the middle
  EXPECT_NEAR(smoothstep(0.0, 1.0, 0.25), 0.15625, 1e-15);  // 3/16 - 2/64
}

TEST(HeightProfile, DensityEqualsClosedFormAtSampleHeights) {
  const HeightRamp r{0.1, 0.3, 0.6, 0.9};
  for (double h = 0.0; h <= 1.0; h += 1.0 / 64) {
    const double expected = hermite(0.1, 0.3, h) - hermite(0.6, 0.9, h);
    EXPECT_NEAR(compute_height_density(r, h), expected, 1e-15) << h;
  }
  EXPECT_EQ(compute_height_density(r, 0.45), 1.0);  // plateau between b and c
  // At the ramp midpoints the density is exactly one half.
  EXPECT_NEAR(compute_height_density(r, 0.2), 0.5, 1e-15);
  EXPECT_NEAR(compute_height_density(r, 0.75), 0.5, 1e-15);
}

TEST(HeightProfile, ErosionIsLinearFromBaseToTop) {
  CloudTypeProfile t{"x", {0.2, 0.3, 0.5, 0.6}, 0.9, 0.1};
  EXPECT_DOUBLE_EQ(compute_height_erosion(t, 0.0), 0.9);
  EXPECT_DOUBLE_EQ(compute_height_erosion(t, 0.2), 0.9);
  EXPECT_NEAR(compute_height_erosion(t, 0.4), 0.5, 1e-15);
  EXPECT_DOUBLE_EQ(compute_height_erosion(t, 0.6), 0.1);
  EXPECT_DOUBLE_EQ(compute_height_erosion(t, 1.0), 0.1);
}

TEST(HeightProfile, RampRulesNameTheField) {
  EXPECT_TRUE(ramp_problems({0.02, 0.05, 0.09, 0.11}, "r").empty());
  EXPECT_TRUE(ramp_problems({0.0, 0.5, 0.5, 1.0}, "r").empty());  // b == c: a peak
  const auto a_after_b = ramp_problems({0.05, 0.02, 0.09, 0.11}, "types[0].density");
  ASSERT_EQ(a_after_b.size(), 1u);
  EXPECT_EQ(a_after_b[0].field, "types[0].density");
  EXPECT_NE(a_after_b[0].message.find("expected a < b <= c < d"), std::string::npos);
  EXPECT_FALSE(ramp_problems({0.1, 0.2, 0.15, 0.3}, "r").empty());  // b > c
  EXPECT_FALSE(ramp_problems({0.1, 0.2, 0.3, 0.3}, "r").empty());   // c == d
  const auto above = ramp_problems({0.1, 0.2, 0.3, 1.5}, "r");
  ASSERT_EQ(above.size(), 1u);
  EXPECT_EQ(above[0].field, "r[3]");
}

TEST(HeightProfile, TypeSetRulesCatchDuplicatesAndErosion) {
  auto types = default_cloud_types();
  EXPECT_TRUE(cloud_type_problems(types).empty());
  types.push_back({"cumulus", {0.1, 0.2, 0.3, 0.4}, 0.5, 0.5});
  types.push_back({"anvil", {0.1, 0.2, 0.3, 0.4}, 1.5, 0.5});
  const auto p = cloud_type_problems(types);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].field, "types[4].name");
  EXPECT_EQ(p[1].field, "types[5].erosion");
}

TEST(HeightProfile, RowHeightMappingRoundTripsAndHitsTexelCentres) {
  const int rows = 37;
  EXPECT_DOUBLE_EQ(height_from_row(0, rows), 0.5 / rows);
  EXPECT_DOUBLE_EQ(height_from_row(rows - 1, rows), 1.0 - 0.5 / rows);
  for (int j = 0; j < rows; ++j)
    EXPECT_NEAR(row_from_height(height_from_row(j, rows), rows), j, 1e-12);
}

TEST(CloudTypes, TypeUMappingRoundTripsAndCentresEachBand) {
  const int types = 5;
  for (int i = 0; i < types; ++i) {
    const double u = type_u_from_index(i, types);
    EXPECT_NEAR(index_from_type_u(u, types), i, 1e-12);
    EXPECT_NEAR(u * types, i + 0.5, 1e-12);  // the centre of column i
  }
  EXPECT_NEAR(index_from_type_u(type_u_from_index(2.25, types), types), 2.25, 1e-12);
}

TEST(CloudTypes, ColumnsFollowTheDocumentedOrderAndEqualTheClosedForm) {
  CloudTypesSpec spec;
  spec.height = 64;
  spec.types.push_back({"anvil", {0.3, 0.5, 0.7, 0.95}, 0.2, 0.8});
  const Texture tex = bake_cloud_types(spec);
  ASSERT_EQ(tex.width, 5);
  ASSERT_EQ(tex.height, 64);
  ASSERT_EQ(tex.channels, (std::vector<std::string>{"R", "G"}));
  const char* names[5] = {"stratus", "stratocumulus", "cumulus", "cumulonimbus", "anvil"};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(meta_string(tex.metadata, "type." + std::to_string(i)), names[i]);
    const CloudTypeProfile& t = spec.types[i];
    for (int j = 0; j < 64; ++j) {
      const double h = (j + 0.5) / 64;  // row 0 = bottom
      const HeightRamp& r = t.density;
      const double density = hermite(r.a, r.b, h) - hermite(r.c, r.d, h);
      EXPECT_NEAR(tex.at(i, j, 0, 0, 0), density, 1e-6) << names[i] << " row " << j;
      const double s = std::clamp((h - r.a) / (r.d - r.a), 0.0, 1.0);
      EXPECT_NEAR(tex.at(i, j, 0, 0, 1), t.erosion_base + s * (t.erosion_top - t.erosion_base),
                  1e-6);
    }
  }
  // Stratus (0.02 .. 0.11) is a thin low sheet: the first column has density
  // only in the bottom rows, cumulus (to 1.0) in the top row as well.
  EXPECT_GT(tex.at(0, 3, 0, 0, 0), 0.0f);
  EXPECT_EQ(tex.at(0, 63, 0, 0, 0), 0.0f);
  EXPECT_GT(tex.at(2, 63, 0, 0, 0), 0.0f);
}

TEST(CloudTypes, ValuesInUnitRangeAndExactlyZeroOutsideTheRamp) {
  CloudTypesSpec spec;
  spec.height = 256;
  const Texture tex = bake_cloud_types(spec);
  for (float v : tex.data) {
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
  }
  for (int i = 0; i < tex.width; ++i) {
    const HeightRamp& r = spec.types[i].density;
    int inside = 0;
    for (int j = 0; j < tex.height; ++j) {
      const double h = height_from_row(j, tex.height);
      const float d = tex.at(i, j, 0, 0, 0);
      if (h <= r.a || h >= r.d) {
        EXPECT_EQ(d, 0.0f) << spec.types[i].name << " h " << h;
      } else {
        EXPECT_GT(d, 0.0f) << spec.types[i].name << " h " << h;
        ++inside;
      }
    }
    EXPECT_GT(inside, 0);
  }
}

TEST(CloudTypes, TypeWidthRepeatsEachColumnInItsBand) {
  CloudTypesSpec spec;
  spec.height = 16;
  spec.type_width = 3;
  const Texture tex = bake_cloud_types(spec);
  ASSERT_EQ(tex.width, 12);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 16; ++j)
        for (int c = 0; c < 2; ++c)
          EXPECT_EQ(tex.at(i * 3 + k, j, 0, 0, c), tex.at(i * 3, j, 0, 0, c));
}

TEST(CloudTypes, BadSpecThrows) {
  CloudTypesSpec spec;
  spec.types[1].density = {0.5, 0.2, 0.6, 0.7};
  EXPECT_THROW(bake_cloud_types(spec), std::exception);
}

TEST(HeightGradients, ChannelsAreTheFirstFourTypeColumns) {
  CloudTypesSpec types;
  types.height = 100;
  HeightGradientsSpec grad;
  grad.height = 100;
  const Texture t = bake_cloud_types(types);
  const Texture g = bake_height_gradients(grad);
  ASSERT_EQ(g.width, 1);
  ASSERT_EQ(g.height, 100);
  ASSERT_EQ(g.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  for (int c = 0; c < 4; ++c)
    for (int j = 0; j < 100; ++j) EXPECT_EQ(g.at(0, j, 0, 0, c), t.at(c, j, 0, 0, 0));
}

}  // namespace
}  // namespace skybake
