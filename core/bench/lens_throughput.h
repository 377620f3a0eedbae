#pragma once
// Lens-tracing throughput, measured in one run on one thread, in rays per second of that thread's
// CPU time, so that the numbers compare directly on a shared machine:
//  * the SML (trace_lens, dT = 3, exact Fresnel, TIR split off as events): polarized spectral rays
//    per second, each ray with one of the 81 spectral wavelengths (the optical constants looked up
//    once per wavelength) and the whole bundle of reflected/refracted rays it spawns traced;
//  * the same lens as an Embree user geometry (attach_lens): rtcIntersect1 first hits;
//  * Embree's own triangles: rtcIntersect1 and rtcIntersect4/8/16 packets of incoherent rays
//    against a 262 144-triangle sphere (the reference figure), and the lens triangulated.
#include <string>
#include <vector>

namespace pmsim {

struct ThroughputResult {
  std::string name;
  double rays_per_s_per_core = 0.0;  // primary rays (SML: input rays, their bundles traced whole)
  double rays = 0.0;
  double seconds = 0.0;
  std::string note;
};

// rays: per measurement (the SML measurement uses rays/4). Single-threaded.
std::vector<ThroughputResult> measure_lens_throughput(int rays);

}  // namespace pmsim
