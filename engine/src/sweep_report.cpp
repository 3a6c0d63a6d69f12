// The sweep's reports: the CSV (one row per point: the swept values,
// cycles, time, status, memory, dominant phase, area, per-phase cycles,
// machine bounds, energy; an interrupted sweep's last row says so) and the
// JSON (the same rows with the swept and fixed parameters, the counts, the
// knees and the exit code).
#include <sstream>
#include <string>
#include <vector>

#include "imap/engine/params_json.hpp"
#include "imap/engine/sweep.hpp"
#include "sweep_detail.hpp"

namespace imap::engine::sweep {

using nlohmann::json;
using namespace detail;

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

std::string to_csv(const Plan& p, const Result& r) {
    std::ostringstream o;
    std::vector<std::string> head;
    for (const Axis& a : p.swept) head.push_back(a.name);
    for (const char* c : {"cycles", "modeled_ms", "fps", "status", "message", "bit_exact", "wall_s",
                          "local_bytes_per_pe", "ext_bytes_per_pe", "dominant_phase",
                          "dominant_share", "area_cells", "area_memory_bits"})
        head.push_back(c);
    for (const std::string& ph : r.phase_names) head.push_back("phase_" + ph);
    head.push_back("bound_cycles");
    head.push_back("efficiency");
    // The phases with a machine bound in some row (docs/firmware.md 11).
    std::vector<std::string> bounded;
    for (const std::string& ph : r.phase_names)
        for (const Row& row : r.rows)
            if (row.ran() && row.run->bound_of(ph) > 0) {
                bounded.push_back(ph);
                break;
            }
    for (const std::string& ph : bounded) head.push_back("bound_" + ph);
    // Energy of the frame and average power over its modeled time
    // (docs/energy.md), after every other column so that their positions stay.
    head.push_back("energy_uj");
    head.push_back("power_mw");
    head.push_back("edp");  // energy x delay, uJ x ms
    auto emit = [&](const std::vector<std::string>& cells) {
        for (size_t i = 0; i < cells.size(); ++i) o << (i ? "," : "") << csv_field(cells[i]);
        o << "\n";
    };
    emit(head);
    for (const Row& row : r.rows) {
        const bool ran = row.ran();
        std::vector<std::string> c = row.values;
        c.push_back(ran ? std::to_string(row.run->cycles) : "");
        c.push_back(ran ? fmt("%.6f", row.run->modeled_ms) : "");
        c.push_back(ran ? fmt("%.4f", row.fps()) : "");
        c.push_back(status_name(row.status));
        c.push_back(row.message);
        c.push_back(ran ? (row.run->bit_exact ? "yes" : "no") : "");
        c.push_back(row.run && row.run->wall_s > 0 ? fmt("%.3f", row.run->wall_s) : "");
        c.push_back(row.local_bytes >= 0 ? std::to_string(row.local_bytes) : "");
        c.push_back(row.ext_bytes >= 0 ? std::to_string(row.ext_bytes) : "");
        c.push_back(ran ? row.run->dominant_phase() : "");
        c.push_back(ran ? fmt("%.4f", row.run->dominant_share()) : "");
        c.push_back(ran && row.run->area ? std::to_string(row.run->area->cells) : "");
        c.push_back(ran && row.run->area ? std::to_string(row.run->area->memory_bits) : "");
        for (const std::string& ph : r.phase_names)
            c.push_back(ran ? std::to_string(phase_cycles(*row.run, ph)) : "");
        const bool bd = ran && row.run->bound_cycles > 0;
        c.push_back(bd ? std::to_string(row.run->bound_cycles) : "");
        c.push_back(bd ? fmt("%.4f", row.run->efficiency()) : "");
        for (const std::string& ph : bounded) {
            const uint64_t b = ran ? row.run->bound_of(ph) : 0;
            c.push_back(b > 0 ? std::to_string(b) : "");
        }
        const bool en = ran && row.run->energy.has_value();
        c.push_back(en ? fmt("%.6f", row.run->energy->total_uj) : "");
        c.push_back(en ? fmt("%.6f", row.run->energy->power_mw) : "");
        c.push_back(en ? fmt("%.6f", metric_value(row, Metric::Edp)) : "");
        emit(c);
    }
    if (r.interrupted) {
        std::vector<std::string> c(head.size());
        c[p.swept.size() + 3] = p.command + "-interrupted";
        c[p.swept.size() + 4] = p.command + " interrupted: " + std::to_string(r.not_run) + " of " +
                                std::to_string(r.total) + " points did not run";
        emit(c);
    }
    return o.str();
}

json to_json(const Plan& p, const Result& r) {
    json j;
    j["command"] = "imapsim " + p.command;
    j["model"] = p.model;
    j["dry_run"] = p.dry_run;
    j["input"] = p.input;
    json sw = json::array();
    for (const Axis& a : p.swept)
        sw.push_back({{"name", a.name}, {"flag", a.flag}, {"values", a.values}});
    j["swept"] = sw;
    j["fixed"] = p.fixed_params;
    j["points_total"] = r.total;
    j["points_finished"] = r.rows.size();
    j["interrupted"] = r.interrupted;
    j["not_run"] = r.not_run;
    if (r.interrupted)
        j["interrupt_message"] = p.command + " interrupted: " + std::to_string(r.not_run) + " of " +
                                 std::to_string(r.total) + " points did not run";
    json counts;
    for (const auto& [st, n] : kStatusNames) counts[n] = r.count(st);
    j["counts"] = counts;
    j["wall_s"] = r.wall_s;
    j["exit_code"] = r.exit_code(p.dry_run);
    j["phase_names"] = r.phase_names;
    json knees = json::array();
    for (const Knee& k : r.knees)
        knees.push_back({{"axis", r.x_axis},
                         {"series", k.series},
                         {"at", k.x},
                         {"modeled_ms", k.y_ms},
                         {"slope_before", k.slope_before},
                         {"slope_after", k.slope_after},
                         {"phase_before", k.phase_before},
                         {"phase_after", k.phase_after},
                         {"explanation", k.explanation},
                         {"label", k.label}});
    j["knees"] = knees;
    json rows = json::array();
    for (const Row& row : r.rows) {
        json o;
        json pt = json::object();
        for (size_t i = 0; i < p.swept.size(); ++i) pt[p.swept[i].name] = row.values[i];
        o["point"] = pt;
        o["status"] = status_name(row.status);
        if (!row.message.empty()) o["message"] = row.message;
        if (row.ran()) {
            const RunResult& rr = *row.run;
            o["cycles"] = rr.cycles;
            o["modeled_ms"] = rr.modeled_ms;
            o["fps"] = row.fps();
            o["bit_exact"] = rr.bit_exact;
            json ph = json::object();
            for (const auto& [n, c] : rr.phases) ph[n] = c;
            o["phases"] = ph;
            o["dominant_phase"] = rr.dominant_phase();
            o["dominant_share"] = rr.dominant_share();
            if (rr.area)
                o["area"] = {{"cells", rr.area->cells}, {"memory_bits", rr.area->memory_bits}};
            if (rr.design_fmax)
                o["design_fmax"] = {{"mhz", rr.design_fmax->mhz},
                                    {"clock_mhz", rr.design_fmax->clock_mhz},
                                    {"clock_above", rr.design_fmax->clock_above},
                                    {"technology", rr.design_fmax->technology}};
            if (rr.bound_cycles > 0) {
                o["bounds"] = bounds_json(rr.bounds);
                o["bound_cycles"] = rr.bound_cycles;
                o["efficiency"] = rr.efficiency();
            }
            if (rr.energy) {
                o["energy"] = energy_json(*rr.energy);
                o["edp"] = metric_value(row, Metric::Edp);
            }
        }
        if (row.run && row.run->wall_s > 0) o["wall_s"] = row.run->wall_s;
        if (row.local_bytes >= 0) o["local_bytes_per_pe"] = row.local_bytes;
        if (row.ext_bytes >= 0) o["ext_bytes_per_pe"] = row.ext_bytes;
        if (row.run && !row.run->command.empty()) o["command"] = row.run->command;
        rows.push_back(o);
    }
    j["rows"] = rows;
    return j;
}

}  // namespace imap::engine::sweep
