#include "imap/engine/result.hpp"

#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "imap/engine/error.hpp"
#include "imap/engine/process.hpp"

namespace imap::engine {

using nlohmann::json;

namespace {

constexpr std::pair<Outcome, const char*> kNames[] = {
    {Outcome::Ok, "ok"},
    {Outcome::Mismatch, "mismatch"},
    {Outcome::InputError, "input-error"},
    {Outcome::Fault, "fault"},
    {Outcome::Failed, "failed"},
    {Outcome::Crashed, "crashed"},
    {Outcome::TimedOut, "timed-out"},
    {Outcome::Cancelled, "cancelled"},
    {Outcome::Interrupted, "interrupted"},
};

// The child's error line without the "error: " prefix.
std::string log_error(const std::string& log) {
    std::string m = child_log_message(log);
    if (m.rfind("error: ", 0) == 0) m = m.substr(7);
    return m.empty() ? "(no output)" : m;
}

}  // namespace

const char* outcome_name(Outcome o) {
    for (const auto& [k, n] : kNames)
        if (k == o) return n;
    return "?";
}

std::optional<Outcome> outcome_from_name(const std::string& s) {
    for (const auto& [k, n] : kNames)
        if (s == n) return k;
    return std::nullopt;
}

bool is_definitive(Outcome o) {
    return o == Outcome::Ok || o == Outcome::Mismatch || o == Outcome::InputError ||
           o == Outcome::Fault;
}

std::string RunResult::dominant_phase() const {
    const auto it =
        std::max_element(phases.begin(), phases.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; });
    return it == phases.end() ? std::string() : it->first;
}

double RunResult::dominant_share() const {
    uint64_t total = 0, top = 0;
    for (const auto& [n, c] : phases) {
        total += c;
        top = std::max(top, c);
    }
    return total ? static_cast<double>(top) / static_cast<double>(total) : 0.0;
}

uint64_t RunResult::bound_of(const std::string& phase) const {
    for (const auto& [n, c] : bounds)
        if (n == phase) return c;
    return 0;
}

double efficiency(uint64_t bound_cycles, uint64_t cycles) {
    return bound_cycles == 0 || cycles == 0
               ? 0.0
               : static_cast<double>(bound_cycles) / static_cast<double>(cycles);
}

double RunResult::efficiency() const {
    return engine::efficiency(bound_cycles, cycles);
}

nlohmann::json bounds_json(const std::vector<std::pair<std::string, uint64_t>>& bounds) {
    nlohmann::json bd = nlohmann::json::object();
    for (const auto& [n, c] : bounds) bd[n] = c;
    return bd;
}

std::string describe(const RunResult& r) {
    switch (r.outcome) {
        case Outcome::Ok:
            return "ok, bit-exact";
        case Outcome::Mismatch: {
            std::string s =
                "not bit-exact vs golden: " + std::to_string(r.differing_pixels) + " pixels differ";
            if (r.first_difference) {
                const FirstDifference& f = *r.first_difference;
                s += ", first at (" + std::to_string(f.x) + "," + std::to_string(f.y) +
                     "): model " + std::to_string(f.model) + ", golden " + std::to_string(f.golden);
            }
            return s;
        }
        case Outcome::InputError:
            return "input error (exit 2): " + r.message;
        case Outcome::Fault:
            return "machine fault (exit 3): " + r.message;
        case Outcome::Crashed:
            return r.message.empty() ? "killed by signal " + std::to_string(r.signal) + " (" +
                                           signal_name(r.signal) + ")"
                                     : r.message;
        case Outcome::Interrupted:
            return r.message.empty() ? std::string("interrupted") : r.message;
        case Outcome::Failed:
        case Outcome::TimedOut:
        case Outcome::Cancelled:
            return r.message.empty() ? std::string(outcome_name(r.outcome)) : r.message;
    }
    return r.message;
}

namespace {

// The machine bounds of a report or a stored result (both write them as an
// object "bounds" and a number "bound_cycles").
void read_bounds(const json& j, RunResult& r) {
    r.bounds.clear();
    if (j.contains("bounds") && j["bounds"].is_object())
        for (const auto& [k, v] : j["bounds"].items()) r.bounds.emplace_back(k, v.get<uint64_t>());
    r.bound_cycles = j.value("bound_cycles", uint64_t{0});
}

// The energy of a report or a stored result (both write it as the object
// "energy"; docs/energy.md).
void read_energy(const json& j, RunResult& r) {
    r.energy.reset();
    if (!j.contains("energy") || !j["energy"].is_object()) return;
    const json& e = j["energy"];
    Energy x;
    x.total_uj = e.at("total_uj").get<double>();
    x.dynamic_uj = e.value("dynamic_uj", 0.0);
    x.static_uj = e.value("static_uj", 0.0);
    x.power_mw = e.value("power_mw", 0.0);
    if (e.contains("by_class") && e["by_class"].is_object())
        for (const auto& [k, v] : e["by_class"].items())
            x.by_class.emplace_back(k, v.get<double>());
    if (e.contains("events") && e["events"].is_object())
        for (const auto& [k, v] : e["events"].items()) x.events.emplace_back(k, v.get<uint64_t>());
    x.events_source = e.value("events_source", std::string());
    r.energy = std::move(x);
}

// The design's Fmax against the clock of a report or a stored result (both
// write it as the object "design_fmax"; docs/rtl.md).
std::optional<DesignFmax> read_design_fmax(const json& j) {
    if (!j.contains("design_fmax") || !j["design_fmax"].is_object()) return std::nullopt;
    const json& f = j["design_fmax"];
    DesignFmax d;
    d.mhz = f.at("mhz").get<double>();
    d.clock_mhz = f.at("clock_mhz").get<double>();
    d.clock_above = f.at("clock_above").get<bool>();
    d.technology = f.value("technology", std::string());
    return d;
}

}  // namespace

json energy_json(const Energy& e) {
    json by = json::object(), ev = json::object();
    for (const auto& [k, v] : e.by_class) by[k] = v;
    for (const auto& [k, v] : e.events) ev[k] = v;
    return {{"total_uj", e.total_uj},
            {"dynamic_uj", e.dynamic_uj},
            {"static_uj", e.static_uj},
            {"power_mw", e.power_mw},
            {"by_class", by},
            {"events", ev},
            {"events_source", e.events_source}};
}

bool read_report(const json& rep, RunResult& r) {
    try {
        if (!rep.is_object() || !rep.contains("cycles") || !rep.contains("phases")) {
            r.message = "report without cycles and phases";
            return false;
        }
        r.cycles = rep.at("cycles").get<uint64_t>();
        r.modeled_ms = rep.at("modeled_ms").get<double>();
        r.bit_exact = rep.value("bit_exact", false);
        r.differing_pixels = rep.value("differing_pixels", uint64_t{0});
        r.first_difference.reset();
        if (rep.contains("first_difference")) {
            const json& f = rep["first_difference"];
            r.first_difference = FirstDifference{f.value("x", -1), f.value("y", -1),
                                                 f.value("model", 0), f.value("golden", 0)};
        }
        r.phases.clear();
        for (const auto& [k, v] : rep.at("phases").items())
            r.phases.emplace_back(k, v.get<uint64_t>());
        r.pe_utilisation = rep.value("pe_utilisation", 0.0);
        read_bounds(rep, r);
        read_energy(rep, r);
        r.area.reset();
        if (rep.contains("area") && rep["area"].is_object()) {
            Area a;
            a.cells = rep["area"].value("cells", uint64_t{0});
            a.memory_bits = rep["area"].value("memory_bits", uint64_t{0});
            r.area = a;
        }
        r.design_fmax = read_design_fmax(rep);
        r.has_report = true;
        return true;
    } catch (const std::exception& e) {
        r.has_report = false;
        r.message = std::string("unreadable report: ") + e.what();
        return false;
    }
}

RunResult read_child(const std::string& model, bool started, int st, const std::string& report,
                     const std::string& log, double wall_s, bool stopped, bool timed_out) {
    RunResult r;
    r.model = model;
    r.wall_s = wall_s;
    r.log = log;
    r.where = "local";
    if (!started) {
        r.outcome = Outcome::Failed;
        r.message = "did not start: " + log_error(log);
        return r;
    }
    if (WIFSIGNALED(st)) {
        r.signal = WTERMSIG(st);
        const std::string sig =
            "signal " + std::to_string(r.signal) + " (" + signal_name(r.signal) + ")";
        if (timed_out) {
            r.outcome = Outcome::TimedOut;
            r.message = "timed out after " + std::to_string(static_cast<long>(wall_s + 0.5)) +
                        " s (killed)";
        } else if (stopped || r.signal == SIGINT || r.signal == SIGTERM) {
            r.outcome = Outcome::Interrupted;
            r.message = "stopped by " + sig;
        } else {
            r.outcome = Outcome::Crashed;
            r.message = "killed by " + sig;
        }
        return r;
    }
    r.exit_code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    if (r.exit_code == kExitInterrupted) {
        r.outcome = Outcome::Interrupted;
        r.message = "stopped (exit 130)";
        return r;
    }
    if (r.exit_code == kExitOk || r.exit_code == kExitMismatch) {
        json rep;
        std::error_code ec;
        if (std::filesystem::exists(report, ec)) {
            try {
                std::ifstream in(report);
                rep = json::parse(in);
            } catch (const std::exception& e) {
                r.outcome = Outcome::Failed;
                r.message =
                    "exit " + std::to_string(r.exit_code) + ", unreadable report: " + e.what();
                return r;
            }
        }
        if (rep.is_null()) {
            r.outcome = Outcome::Failed;
            r.message = "exit " + std::to_string(r.exit_code) + ", no report: " + log_error(log);
            return r;
        }
        if (!read_report(rep, r)) {
            r.outcome = Outcome::Failed;
            r.message = "exit " + std::to_string(r.exit_code) + ", " + r.message;
            return r;
        }
        if (!r.bit_exact) {
            r.outcome = Outcome::Mismatch;
            r.message.clear();
        } else if (r.exit_code == kExitOk) {
            r.outcome = Outcome::Ok;
        } else {
            r.outcome = Outcome::Failed;
            r.message = "bit-exact report but exit " + std::to_string(r.exit_code);
        }
        return r;
    }
    switch (r.exit_code) {
        case kExitInput:
            r.outcome = Outcome::InputError;
            r.message = log_error(log);
            break;
        case kExitFault:
            r.outcome = Outcome::Fault;
            r.message = log_error(log);
            break;
        default:
            r.outcome = Outcome::Failed;
            r.message = "exit " + std::to_string(r.exit_code) + ": " + log_error(log);
    }
    return r;
}

json to_json(const RunResult& r) {
    json j;
    j["model"] = r.model;
    j["outcome"] = outcome_name(r.outcome);
    j["exit_code"] = r.exit_code;
    if (r.signal) j["signal"] = r.signal;
    if (!r.message.empty()) j["message"] = r.message;
    j["has_report"] = r.has_report;
    if (r.has_report) {
        j["bit_exact"] = r.bit_exact;
        j["differing_pixels"] = r.differing_pixels;
        if (r.first_difference)
            j["first_difference"] = {{"x", r.first_difference->x},
                                     {"y", r.first_difference->y},
                                     {"model", r.first_difference->model},
                                     {"golden", r.first_difference->golden}};
        j["cycles"] = r.cycles;
        j["modeled_ms"] = r.modeled_ms;
        json ph = json::array();
        for (const auto& [n, c] : r.phases) ph.push_back({n, c});
        j["phases"] = ph;  // an array of pairs: keeps the program's order
        if (r.area) j["area"] = {{"cells", r.area->cells}, {"memory_bits", r.area->memory_bits}};
        if (r.design_fmax)
            j["design_fmax"] = {{"mhz", r.design_fmax->mhz},
                                {"clock_mhz", r.design_fmax->clock_mhz},
                                {"clock_above", r.design_fmax->clock_above},
                                {"technology", r.design_fmax->technology}};
        j["pe_utilisation"] = r.pe_utilisation;
        if (r.bound_cycles > 0) {
            j["bounds"] = bounds_json(r.bounds);
            j["bound_cycles"] = r.bound_cycles;
        }
        if (r.energy) j["energy"] = energy_json(*r.energy);
    }
    j["wall_s"] = r.wall_s;
    if (!r.where.empty()) j["where"] = r.where;
    if (!r.log.empty()) j["log"] = r.log;
    if (!r.command.empty()) j["command"] = r.command;
    return j;
}

RunResult result_from_json(const json& j) {
    RunResult r;
    r.model = j.at("model").get<std::string>();
    const auto o = outcome_from_name(j.at("outcome").get<std::string>());
    if (!o) throw std::invalid_argument("unknown outcome " + j.at("outcome").dump());
    r.outcome = *o;
    r.exit_code = j.value("exit_code", -1);
    r.signal = j.value("signal", 0);
    r.message = j.value("message", std::string());
    r.has_report = j.value("has_report", false);
    if (r.has_report) {
        r.bit_exact = j.at("bit_exact").get<bool>();
        r.differing_pixels = j.value("differing_pixels", uint64_t{0});
        if (j.contains("first_difference")) {
            const json& f = j["first_difference"];
            r.first_difference =
                FirstDifference{f.at("x").get<int>(), f.at("y").get<int>(),
                                f.at("model").get<int>(), f.at("golden").get<int>()};
        }
        r.cycles = j.at("cycles").get<uint64_t>();
        r.modeled_ms = j.at("modeled_ms").get<double>();
        for (const json& p : j.at("phases"))
            r.phases.emplace_back(p.at(0).get<std::string>(), p.at(1).get<uint64_t>());
        if (j.contains("area"))
            r.area = Area{j["area"].at("cells").get<uint64_t>(),
                          j["area"].at("memory_bits").get<uint64_t>()};
        r.design_fmax = read_design_fmax(j);
        r.pe_utilisation = j.value("pe_utilisation", 0.0);
        read_bounds(j, r);
        read_energy(j, r);
    }
    r.wall_s = j.value("wall_s", 0.0);
    r.where = j.value("where", std::string());
    r.log = j.value("log", std::string());
    r.command = j.value("command", std::string());
    return r;
}

}  // namespace imap::engine
