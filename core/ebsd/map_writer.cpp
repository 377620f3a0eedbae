#include "core/ebsd/map_writer.h"

#include <charconv>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "core/base/units.h"

namespace pmsim {

namespace {

// Text appended into one growing buffer, flushed in large blocks.
class Out {
 public:
  explicit Out(const std::string& path) : path_(path), f_(std::fopen(path.c_str(), "wb"), &std::fclose) {
    if (!f_) throw std::runtime_error("cannot write " + path);
    buf_.reserve(kBlock + 4096);
  }
  Out& operator<<(std::string_view s) {
    buf_.append(s);
    if (buf_.size() > kBlock) flush();
    return *this;
  }
  // Shortest form that reads back to the same float/double (std::to_chars).
  template <class T>
  Out& num(T v) {
    char tmp[64];
    const auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
    return *this << std::string_view(tmp, static_cast<std::size_t>(r.ptr - tmp));
  }
  void flush() {
    if (!buf_.empty() && std::fwrite(buf_.data(), 1, buf_.size(), f_.get()) != buf_.size())
      throw std::runtime_error("cannot write " + path_);
    buf_.clear();
  }
  void close() {
    flush();
    if (std::fclose(f_.release()) != 0) throw std::runtime_error("cannot write " + path_);
  }

 private:
  static constexpr std::size_t kBlock = 1 << 20;
  std::string path_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f_;
  std::string buf_;
};

int ctf_laue_number(const std::string& symbol) {
  static const char* const kLaue[] = {"-1", "2/m", "mmm", "4/m", "4/mmm", "-3", "-3m", "6/m", "6/mmm", "m-3", "m-3m"};
  for (int k = 0; k < 11; ++k)
    if (symbol == kLaue[k]) return k + 1;
  return 1;
}

const char* ang_symmetry_code(const std::string& symbol) {
  static const char* const kLaue[][2] = {{"-1", "1"},   {"2/m", "20"}, {"mmm", "22"},  {"4/m", "4"},
                                         {"4/mmm", "42"}, {"-3", "3"},   {"-3m", "32"},  {"6/m", "6"},
                                         {"6/mmm", "62"}, {"m-3", "23"}, {"m-3m", "43"}};
  for (const auto& e : kLaue)
    if (symbol == e[0]) return e[1];
  return "1";
}

}  // namespace

void write_ctf(const OrientationMap& m, const std::string& path) {
  Out o(path);
  o << "Channel Text File\r\nPrj\tpmsim\r\nAuthor\tpmsim\r\nJobMode\tGrid\r\nXCells\t";
  o.num(m.columns_odd) << "\r\nYCells\t";
  o.num(m.rows) << "\r\nXStep\t";
  o.num(m.step_x_um) << "\r\nYStep\t";
  o.num(m.step_y_um) << "\r\nAcqE1\t0\r\nAcqE2\t0\r\nAcqE3\t0\r\n";
  o << "Euler angles refer to Sample Coordinate system (CS0)!\tMag\t100\tCoverage\t100\tDevice\t0\tKV\t20\t"
       "TiltAngle\t70\tTiltAxis\t0\r\nPhases\t";
  o.num(static_cast<int>(m.phases.size())) << "\r\n";
  for (const EbsdPhase& p : m.phases) {
    o.num(p.cell.a_A) << ";";
    o.num(p.cell.b_A) << ";";
    o.num(p.cell.c_A) << "\t";
    o.num(p.cell.alpha_deg) << ";";
    o.num(p.cell.beta_deg) << ";";
    o.num(p.cell.gamma_deg) << "\t" << p.name << "\t";
    o.num(ctf_laue_number(p.laue_group)) << "\t";
    o.num(p.space_group) << "\r\n";
  }
  o << "Phase\tX\tY\tBands\tError\tEuler1\tEuler2\tEuler3\tMAD\tBC\tBS\r\n";
  for (std::size_t i = 0; i < m.size(); ++i) {
    const bool ix = m.indexed(i);
    o.num(static_cast<int>(m.phase[i])) << "\t";
    o.num(static_cast<float>(m.origin_x_um + m.x_um(i))) << "\t";
    o.num(static_cast<float>(m.origin_y_um + m.y_um(i))) << (ix ? "\t8\t0\t" : "\t0\t3\t");
    o.num(ix ? static_cast<float>(degrees(m.phi1_rad[i])) : 0.0f) << "\t";
    o.num(ix ? static_cast<float>(degrees(m.Phi_rad[i])) : 0.0f) << "\t";
    o.num(ix ? static_cast<float>(degrees(m.phi2_rad[i])) : 0.0f) << (ix ? "\t0.5\t150\t160\r\n" : "\t0\t20\t30\r\n");
  }
  o.close();
}

void write_ang(const OrientationMap& m, const std::string& path) {
  Out o(path);
  o << "# TEM_PIXperUM          1.000000\n";
  for (const EbsdPhase& p : m.phases) {
    o << "#\n# Phase ";
    o.num(p.id) << "\n# MaterialName  \t" << p.name << "\n# Formula     \t" << p.formula << "\n# Info\n# Symmetry    \t"
                << ang_symmetry_code(p.laue_group) << "\n# LatticeConstants\t";
    o.num(p.cell.a_A) << " ";
    o.num(p.cell.b_A) << " ";
    o.num(p.cell.c_A) << " ";
    o.num(p.cell.alpha_deg) << " ";
    o.num(p.cell.beta_deg) << " ";
    o.num(p.cell.gamma_deg) << "\n# NumberFamilies\t0\n";
  }
  o << "#\n# GRID: " << (m.grid == MapGrid::Hexagonal ? "HexGrid" : "SqrGrid") << "\n# XSTEP: ";
  o.num(m.step_x_um) << "\n# YSTEP: ";
  o.num(m.step_y_um) << "\n# NCOLS_ODD: ";
  o.num(m.columns_odd) << "\n# NCOLS_EVEN: ";
  o.num(m.columns_even) << "\n# NROWS: ";
  o.num(m.rows) << "\n#\n# OPERATOR: \tpmsim\n#\n";
  const bool single = m.phases.size() == 1;
  const float sentinel = static_cast<float>(4.0 * kPi);
  for (std::size_t i = 0; i < m.size(); ++i) {
    const bool ix = m.indexed(i);
    o.num(ix ? m.phi1_rad[i] : sentinel) << " ";
    o.num(ix ? m.Phi_rad[i] : sentinel) << " ";
    o.num(ix ? m.phi2_rad[i] : sentinel) << " ";
    o.num(static_cast<float>(m.origin_x_um + m.x_um(i))) << " ";
    o.num(static_cast<float>(m.origin_y_um + m.y_um(i))) << (ix ? " 500.0 0.8 " : " 0.0 -1 ");
    o.num(ix ? (single ? 0 : static_cast<int>(m.phase[i])) : 0) << (ix ? " 1000 0.7\n" : " 0 180\n");
  }
  o.close();
}

}  // namespace pmsim
