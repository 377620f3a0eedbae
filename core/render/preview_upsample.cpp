#include "core/render/preview_upsample.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/microscope/view_geometry.h"

namespace pmsim {

void upsample_preview(const Scene& scene, const EvaluationPlan& coarse_plan, const RenderImage& coarse,
                      RenderImage& full) {
  const int W = scene.render.width, H = scene.render.height;
  const int cw = coarse.width, ch = coarse.height;
  // Spread over the full grid. field_from_pixel is separable (x from the column, y from the
  // row), so the coarse-grid position and bilinear weights are tabulated once per column and
  // row; the per-pixel work is the lit test and four weighted reads (the upsampling was over half
  // of the preview when every pixel recomputed its field point and direction).
  struct Axis {
    double f2 = 0.0;             // square of the field coordinate of the pixel centre
    int c0 = 0, c1 = 0;          // the two coarse cells around it (clamped into the grid)
    float w0 = 0.0f, w1 = 0.0f;  // their bilinear weights (0 for a cell outside the grid)
    int nearest = 0;             // nearest coarse cell (clamped)
  };
  const double half_c = 0.5 * std::min(cw, ch);
  auto make_axis = [&](int n_full, int n_coarse, bool is_x) {
    std::vector<Axis> a(n_full);
    for (int i = 0; i < n_full; ++i) {
      const glm::dvec2 f = is_x ? field_from_pixel(W, H, i + 0.5, 0.5) : field_from_pixel(W, H, 0.5, i + 0.5);
      const double fc = is_x ? f.x : f.y;
      // The same field point on the coarse grid (pixel centres at i + 0.5; y grows downwards).
      const double g = is_x ? fc * half_c + 0.5 * n_coarse - 0.5 : 0.5 * n_coarse - fc * half_c - 0.5;
      const int i0 = static_cast<int>(std::floor(g));
      const float t = static_cast<float>(g - i0);
      a[i].f2 = fc * fc;
      a[i].c0 = std::clamp(i0, 0, n_coarse - 1);
      a[i].c1 = std::clamp(i0 + 1, 0, n_coarse - 1);
      a[i].w0 = (i0 >= 0 && i0 < n_coarse) ? 1.0f - t : 0.0f;
      a[i].w1 = (i0 + 1 >= 0 && i0 + 1 < n_coarse) ? t : 0.0f;
      a[i].nearest = std::clamp(static_cast<int>(std::lround(g)), 0, n_coarse - 1);
    }
    return a;
  };
  const std::vector<Axis> ax = make_axis(W, cw, true), ay = make_axis(H, ch, false);
  // Coarse cells as 7 floats: rgb, xyz, lit (1 or 0).
  std::vector<float> cell(static_cast<std::size_t>(cw) * ch * 7);
  for (std::size_t i = 0; i < static_cast<std::size_t>(cw) * ch; ++i) {
    for (int k = 0; k < 3; ++k) {
      cell[7 * i + k] = coarse.rgb[3 * i + k];
      cell[7 * i + 3 + k] = coarse.xyz[3 * i + k];
    }
    cell[7 * i + 6] = coarse_plan.pixel_lit(i) ? 1.0f : 0.0f;
  }
  // Back focal plane: lit where bfp_direction is (|f| ≤ 1 and |f|·NA_objective ≤ NA_condenser);
  // surely lit well inside that radius.
  const bool bfp = scene.mode == ViewMode::Cono && scene.bertrand_in;
  const double rho_lit = std::min(1.0, scene.condenser.na / scene.objective.na);
  const double lit_sure = 0.99 * rho_lit * rho_lit;
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y) {
      const Axis& Y = ay[y];
      const float* row0 = cell.data() + 7 * static_cast<std::size_t>(Y.c0) * cw;
      const float* row1 = cell.data() + 7 * static_cast<std::size_t>(Y.c1) * cw;
      float* out_rgb = full.rgb.data() + 3 * static_cast<std::size_t>(y) * W;
      float* out_xyz = full.xyz.data() + 3 * static_cast<std::size_t>(y) * W;
      for (int x = 0; x < W; ++x) {
        const Axis& X = ax[x];
        if (bfp) {
          // The test of bfp_direction, with the square root only near the rim.
          const double s2 = X.f2 + Y.f2;
          if (s2 > lit_sure) {
            if (!bfp_lit(scene, std::sqrt(s2))) {  // unlit: black
              for (int c3 = 0; c3 < 3; ++c3) out_rgb[3 * x + c3] = out_xyz[3 * x + c3] = 0.0f;
              continue;
            }
          }
        }
        // Four neighbours; out-of-grid ones have weight 0, unlit ones carry lit = 0.
        const float* c[4] = {row0 + 7 * X.c0, row0 + 7 * X.c1, row1 + 7 * X.c0, row1 + 7 * X.c1};
        const float w[4] = {Y.w0 * X.w0 * c[0][6], Y.w0 * X.w1 * c[1][6], Y.w1 * X.w0 * c[2][6],
                            Y.w1 * X.w1 * c[3][6]};
        const float wsum = w[0] + w[1] + w[2] + w[3];
        float acc[6];
        if (wsum > 0.0f) {
          const float inv = 1.0f / wsum;
          for (int k = 0; k < 6; ++k)
            acc[k] = (w[0] * c[0][k] + w[1] * c[1][k] + w[2] * c[2][k] + w[3] * c[3][k]) * inv;
        } else {  // at the rim: the nearest coarse sample
          const float* n = cell.data() + 7 * (static_cast<std::size_t>(Y.nearest) * cw + X.nearest);
          for (int k = 0; k < 6; ++k) acc[k] = n[k];
        }
        for (int c3 = 0; c3 < 3; ++c3) {
          out_rgb[3 * x + c3] = acc[c3];
          out_xyz[3 * x + c3] = acc[3 + c3];
        }
      }
    }
  });
}

}  // namespace pmsim
