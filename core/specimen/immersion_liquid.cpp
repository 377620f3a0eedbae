#include "core/specimen/immersion_liquid.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "core/base/asset_locator.h"
#include "core/base/json_reader.h"
#include "core/optics/cauchy.h"

namespace pmsim {

namespace {

struct Anchor {
  double nd, dispersion;  // n_D, n_F − n_C
};
struct Series {
  double lambda_c_nm = 656.28, lambda_d_nm = 589.26, lambda_f_nm = 486.13;
  std::vector<Anchor> anchors;  // by increasing n_D
};

const Series& series() {
  static const Series s = [] {
    const std::string file = (std::filesystem::path(asset_dir()) / "liquids" / "immersion_liquids.json").string();
    const nlohmann::json j = read_json_file(file, "immersion liquid series");
    const JsonReader r(j, file);
    Series out;
    const JsonReader w = r.object("wavelengths_nm");
    out.lambda_c_nm = w.require<double>("C", Range::open(380, 780));
    out.lambda_d_nm = w.require<double>("D", Range::open(380, 780));
    out.lambda_f_nm = w.require<double>("F", Range::open(380, 780));
    for (const JsonReader& l : r.objects("liquids", 2)) {
      const double nc = l.require<double>("nC", Range::open(1, 3));
      const double nd = l.require<double>("nD", Range::open(1, 3));
      const double nf = l.require<double>("nF", Range::open(1, 3));
      if (!(nc < nd && nd < nf)) l.fail("nD", "normal dispersion needs nC < nD < nF");
      out.anchors.push_back({nd, nf - nc});
    }
    std::sort(out.anchors.begin(), out.anchors.end(), [](const Anchor& a, const Anchor& b) { return a.nd < b.nd; });
    return out;
  }();
  return s;
}

// n_F − n_C of the series at n_D: linear between measured liquids; beyond the first and last at
// their Abbe number v_D = (n_D − 1)/(n_F − n_C), the usual way a liquid series' dispersion scales.
double series_dispersion(const Series& s, double nd) {
  const auto& a = s.anchors;
  if (nd <= a.front().nd) return a.front().dispersion * (nd - 1.0) / (a.front().nd - 1.0);
  if (nd >= a.back().nd) return a.back().dispersion * (nd - 1.0) / (a.back().nd - 1.0);
  for (std::size_t i = 1; i < a.size(); ++i)
    if (nd <= a[i].nd) {
      const double t = (nd - a[i - 1].nd) / (a[i].nd - a[i - 1].nd);
      return a[i - 1].dispersion + t * (a[i].dispersion - a[i - 1].dispersion);
    }
  return a.back().dispersion;
}

ImmersionLiquid make_liquid(double nd, double dispersion, const Series& s) {
  ImmersionLiquid l;
  l.nd = nd;
  l.nf_minus_nc = dispersion;
  l.B_nm2 = dispersion / (1.0 / (s.lambda_f_nm * s.lambda_f_nm) - 1.0 / (s.lambda_c_nm * s.lambda_c_nm));
  l.A = nd - l.B_nm2 / (s.lambda_d_nm * s.lambda_d_nm);
  return l;
}

}  // namespace

double ImmersionLiquid::n(double wavelength_nm) const { return cauchy_index(A, B_nm2, 0.0, wavelength_nm); }

ImmersionLiquid immersion_liquid(double nd) {
  if (!(nd >= 1.40 && nd <= 1.80)) throw std::invalid_argument("immersion liquid n_D outside 1.40…1.80");
  const Series& s = series();
  return make_liquid(nd, series_dispersion(s, nd), s);
}

ImmersionLiquid immersion_liquid(double nd, double nf_minus_nc) {
  return make_liquid(nd, nf_minus_nc, Series{});
}

}  // namespace pmsim
