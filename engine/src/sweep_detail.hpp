// The sweep engine's private pieces shared by its files (engine/src/sweep_*.cpp):
// the algorithm parameters an axis may set, the status names of the reports,
// and the helpers that more than one stage needs (ROI sizes, series labels,
// phase cycles, a point and a metric in words).
#pragma once

#include <cstdint>
#include <string>
#include <utility>

#include "imap/engine/result.hpp"
#include "imap/engine/sweep.hpp"
#include "imap/golden/params.hpp"

namespace imap::engine::sweep::detail {

// "WxH" (each at most 1000000); false if it is not that.
bool parse_wxh(const std::string& v, int* w, int* h);

// The integer algorithm parameters an axis may set, their ranges and fields.
struct AlgoInt {
    const char* name;
    long long lo, hi;
    int golden::Params::*field;
};
inline const AlgoInt kAlgoInts[] = {{"D", 1, golden::kMaxLevels, &golden::Params::D},
                                    {"km", 0, golden::kMaxWeight, &golden::Params::km},
                                    {"kb", 0, golden::kMaxWeight, &golden::Params::kb},
                                    {"gb", 0, 255, &golden::Params::gb},
                                    {"Wo", 0, golden::kMaxWeight, &golden::Params::Wo},
                                    {"Wd", 0, golden::kMaxWeight, &golden::Params::Wd}};

// The reports' names of the statuses.
inline constexpr std::pair<Status, const char*> kStatusNames[] = {
    {Status::Ok, "ok"},
    {Status::Mismatch, "mismatch"},
    {Status::DoesNotFit, "does-not-fit"},
    {Status::CannotRun, "cannot-run"},
    {Status::Planned, "fits-not-run"},
    {Status::Error, "error"},
    {Status::Interrupted, "interrupted"},
};

// The other swept axes' values of a row, its series along axis xi ("D=64"
// along pes when pes and D are swept; "" with one swept axis)
// (sweep_knees.cpp).
std::string series_label(const Plan& p, const Row& r, size_t xi);
// The cycles of phase n in a run (0 if it has none) (sweep_knees.cpp).
uint64_t phase_cycles(const RunResult& r, const std::string& n);
// "pes=256, D=64": a row's swept values (the whole point when nothing is
// swept) (sweep_table.cpp).
std::string point_text(const Plan& p, const Row& r);
// A metric's value with its unit, "-" for NaN (sweep_table.cpp).
std::string metric_text(Metric m, double v);

}  // namespace imap::engine::sweep::detail
