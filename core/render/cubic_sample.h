#pragma once
// Keys' cubic convolution read four samples at a time (SIMD lanes), of a one-channel field or of a
// field of four floats a point (X, Y, Z, 0): what the specimen response's and the conoscopic
// figure's composers read their turned grids with.
#include <algorithm>
#include <cstddef>
#include <cstring>

namespace pmsim::cubic {

// Four floats in one SIMD register (GCC's vector extension: SSE on x86-64, NEON on arm64).
using v4 = float __attribute__((vector_size(16)));
inline v4 load4(const float* p) {
  v4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store4(float* p, const v4& v) { std::memcpy(p, &v, sizeof v); }

// Lanes p of four vectors a[p] as vectors of lane p: the 4 × 4 transpose.
inline void transpose(v4 a[4]) {
  const v4 t0 = __builtin_shufflevector(a[0], a[1], 0, 4, 1, 5), t1 = __builtin_shufflevector(a[0], a[1], 2, 6, 3, 7);
  const v4 t2 = __builtin_shufflevector(a[2], a[3], 0, 4, 1, 5), t3 = __builtin_shufflevector(a[2], a[3], 2, 6, 3, 7);
  a[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  a[1] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  a[2] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  a[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// Catmull–Rom (Keys 1981, a = −½) weights of the four points around fractional position t, for
// four samples at once (lane p: sample p).
inline void keys_weights(v4 t, v4 w[4]) {
  const v4 t2 = t * t, t3 = t2 * t;
  w[0] = -0.5f * t3 + t2 - 0.5f * t;
  w[1] = 1.5f * t3 - 2.5f * t2 + 1.0f;
  w[2] = -1.5f * t3 + 2.0f * t2 + 0.5f * t;
  w[3] = 0.5f * t3 - 0.5f * t2;
}

// Where four samples read a field of w × h points (positions in point units, clamped to it):
// the point at or below each (x0, y0) and the fraction past it.
struct Cell4 {
  int x0[4], y0[4];
  v4 fx, fy;
};
[[gnu::always_inline]] inline Cell4 cells(const double (&x)[4], const double (&y)[4], int w, int h, int x_max, int y_max) {
  Cell4 c;
  for (int p = 0; p < 4; ++p) {
    const double cx = std::clamp(x[p], 0.0, double(w - 1)), cy = std::clamp(y[p], 0.0, double(h - 1));
    c.x0[p] = std::min(int(cx), x_max);
    c.y0[p] = std::min(int(cy), y_max);
    c.fx[p] = float(cx - c.x0[p]);
    c.fy[p] = float(cy - c.y0[p]);
  }
  return c;
}

// Cubic convolution (Keys 1981): interpolating, and its passband is flat far closer to the grid's
// Nyquist limit than a bilinear tent's, so that a turned stage adds little blur to the
// tent-splatted grid (a fresh render at that angle has the splat's blur only). Four samples of a
// one-channel field of w × h points, separably: each column of a sample's 4 × 4 points weighted by
// wy, then the four columns by wx (lane p: sample p). At a whole point (fraction 0: weights 0, 1,
// 0, 0) a sample is that point's value exactly.
inline v4 cubic1(const float* v, int w, int h, const Cell4& c) {
  v4 wx[4], wy[4], col[4];
  keys_weights(c.fx, wx);
  keys_weights(c.fy, wy);
  const std::size_t sw = std::size_t(w);
  for (int p = 0; p < 4; ++p) {
    const int x0 = c.x0[p], y0 = c.y0[p];
    v4 row[4];
    if (x0 >= 1 && x0 + 2 < w && y0 >= 1 && y0 + 2 < h) {  // inside: 4 rows of 4 adjacent points
      const float* q = v + std::size_t(y0 - 1) * sw + std::size_t(x0 - 1);
      for (std::size_t j = 0; j < 4; ++j) row[j] = load4(q + j * sw);
    } else {
      for (int j = 0; j < 4; ++j) {
        const float* q = v + std::size_t(std::clamp(y0 - 1 + j, 0, h - 1)) * sw;
        for (int i = 0; i < 4; ++i) row[j][i] = q[std::clamp(x0 - 1 + i, 0, w - 1)];
      }
    }
    col[p] = wy[0][p] * row[0] + wy[1][p] * row[1] + wy[2][p] * row[2] + wy[3][p] * row[3];
  }
  transpose(col);  // col[i]: column i of each sample
  return wx[0] * col[0] + wx[1] * col[1] + wx[2] * col[2] + wx[3] * col[3];
}

// The same for a field of 4 floats a point (X, Y, Z, 0): out[p] is sample p's X, Y, Z, 0.
inline void cubic4(const float* v, int w, int h, const Cell4& c, v4 out[4]) {
  v4 wx[4], wy[4];
  keys_weights(c.fx, wx);
  keys_weights(c.fy, wy);
  const std::size_t sw = std::size_t(w);
  for (int p = 0; p < 4; ++p) {
    const int x0 = c.x0[p], y0 = c.y0[p];
    std::size_t ys[4], xs[4];
    if (x0 >= 1 && x0 + 2 < w && y0 >= 1 && y0 + 2 < h) {  // inside: no clamping
      for (std::size_t k = 0; k < 4; ++k) {
        ys[k] = (std::size_t(y0 - 1) + k) * sw;
        xs[k] = std::size_t(x0 - 1) + k;
      }
    } else {
      for (int k = 0; k < 4; ++k) {
        ys[k] = std::size_t(std::clamp(y0 - 1 + k, 0, h - 1)) * sw;
        xs[k] = std::size_t(std::clamp(x0 - 1 + k, 0, w - 1));
      }
    }
    v4 sum{};
    for (std::size_t i = 0; i < 4; ++i) {
      const v4 col = wy[0][p] * load4(v + 4 * (ys[0] + xs[i])) + wy[1][p] * load4(v + 4 * (ys[1] + xs[i])) +
                     wy[2][p] * load4(v + 4 * (ys[2] + xs[i])) + wy[3][p] * load4(v + 4 * (ys[3] + xs[i]));
      sum = i == 0 ? wx[0][p] * col : sum + wx[i][p] * col;
    }
    out[p] = sum;
  }
}

}  // namespace pmsim::cubic
