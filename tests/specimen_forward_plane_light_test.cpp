// Plane light traced forward from the condenser (core/specimen/forward_plane_light.h): the same
// image as the backward renderer by reciprocity, exactly 1 wherever the specimen only translates
// the light, and the Becke line's physics (direction with the indices and the focus) unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/specimen/forward_plane_light.h"
#include "core/specimen/plane_light_image.h"
#include "specimen_fixture.h"

namespace {

using specimen_test::band_mean;
using specimen_test::make_specimen;
using specimen_test::mono_view;
using specimen_test::OneFragment;
using specimen_test::signed_distance;

// Mean Y in bands of signed distance from the outline (µm; + inside the fragment).
std::vector<double> profile(const pmsim::RenderImage& img, const std::vector<double>& d,
                            const std::vector<double>& edges) {
  std::vector<double> p;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) p.push_back(band_mean(img, d, edges[i], edges[i + 1]));
  return p;
}

const std::vector<double> kEdges = {-30, -16, -10, -6, -3, -1, 1, 3, 6, 10, 16, 30};

}  // namespace

// The empty field and a fragment matched to its liquid (every medium of index 1.54): the light is
// only translated, so every pixel of every pass receives tent weights summing to 1 — the image is
// 1 after ONE pass (the backward renderer needs many for its annulus to average out). Tolerance
// 1e-3: Embree's hit points are float (6e-5 µm at the slide's 1000 µm) and each face nudges a ray
// 1e-3 µm off it, which moves a landing by ≲ 4e-4 of a 2.5 µm pixel; the matched fragment's
// Fresnel terms are 0 (equal indices). A sampler with any noise would be off by 1e-2 or more.
TEST(SpecimenForwardPlaneLight, MatchedIndicesAreExactlyUniformAfterOnePass) {
  OneFragment f;
  f.n_fragment = 1.54;
  const auto scene = make_specimen(f);
  pmsim::PlaneLightOptions o = mono_view(10.0, 1);
  o.width = o.height = 64;
  o.um_per_px = 2.5;
  const pmsim::RenderImage img = pmsim::render_plane_light_forward(*scene, o);
  double lo = 1e9, hi = -1e9;
  for (std::size_t i = 0; i < img.xyz.size() / 3; ++i) {
    lo = std::min(lo, double(img.xyz[3 * i + 1]));
    hi = std::max(hi, double(img.xyz[3 * i + 1]));
  }
  std::printf("matched fragment, one pass: Y in [%.6f, %.6f]\n", lo, hi);
  EXPECT_NEAR(lo, 1.0, 1e-3);
  EXPECT_NEAR(hi, 1.0, 1e-3);
}

// Reciprocity: forward and backward give the same image. Compared as the mean Y in bands of
// distance from the outline of a fragment (n 1.60 in 1.54, focused 10 µm up: the Becke line
// inside), with the condenser opened to NA 0.15 under the objective's 0.25 so the backward
// sampler converges in the test's time too. Tolerance 0.03 on band means of 1 (Becke line 1.2,
// rim 0.5): the backward bands' noise at 384 paths is ~0.005 (its split halves), the forward's
// less (the tent filter, 2 px wide against the backward box, blurs the rim band by ~0.01); a wrong focal plane, start shift or normalization moves the Becke line's bands by 0.1–0.5.
TEST(SpecimenForwardPlaneLight, MatchesTheBackwardRenderer) {
  const auto scene = make_specimen(OneFragment{});
  pmsim::PlaneLightOptions o = mono_view(10.0, 384);
  o.width = o.height = 120;
  o.um_per_px = 4.0 / 3.0;
  o.condenser_aperture_na = 0.15;
  const std::vector<double> d = signed_distance(*scene, o);
  const pmsim::RenderImage back = pmsim::render_plane_light(*scene, o);
  pmsim::PlaneLightOptions of = o;
  of.spp = 64;
  const pmsim::RenderImage fwd = pmsim::render_plane_light_forward(*scene, of);
  const std::vector<double> pb = profile(back, d, kEdges), pf = profile(fwd, d, kEdges);
  for (std::size_t i = 0; i < pb.size(); ++i)
    std::printf("  [%+3.0f, %+3.0f) µm: backward %.4f forward %.4f\n", kEdges[i], kEdges[i + 1], pb[i], pf[i]);
  for (std::size_t i = 0; i < pb.size(); ++i) EXPECT_NEAR(pf[i], pb[i], 0.03) << "band " << i;
}
