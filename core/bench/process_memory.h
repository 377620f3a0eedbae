#pragma once
// The process's resident memory from /proc/self (Linux), for the bench rows that state a memory
// bound beside their time (EBSD map loading, rock growth).
namespace pmsim {

// A "kB" field of /proc/self/status ("VmRSS", "VmHWM"); −1 when /proc is not available.
long process_status_kb(const char* key);

// Resets the process's peak RSS to the current one (Linux ≥ 4.0: "5" to clear_refs), so that
// VmHWM afterwards is the peak of what follows.
void reset_peak_rss();

}  // namespace pmsim
