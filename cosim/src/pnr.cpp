// The design's place-and-route figures (imap/rtl/pnr.hpp): parses the JSON
// of scripts/rtl-pnr.sh embedded by cmake/embed_files.cmake, and
// states the Fmax against a clock.
#include "imap/rtl/pnr.hpp"

#include "sha256.hpp"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>
#include <vector>

namespace imap::rtl {

namespace detail::pnr {
// rtl_model/synth/pnr_ice40.json (rtl_model/CMakeLists.txt embeds it)
const std::vector<std::pair<const char*, const char*>>& embedded_sources();
}  // namespace detail::pnr
namespace detail {
// the RTL sources of this build (rtl_sources.cpp; paths relative to rtl_model/)
const std::vector<std::pair<const char*, const char*>>& embedded_sources();
}  // namespace detail

namespace {
uint64_t positive(const nlohmann::json& o, const char* key, const char* where) {
    if (!o.contains(key) || !o[key].is_number_unsigned() || o[key].get<uint64_t>() == 0)
        throw std::runtime_error(std::string("place-and-route figures: ") + where + "." + key +
                                 " missing or not a positive integer");
    return o[key].get<uint64_t>();
}
PnrUnit unit(const nlohmann::json& o, const char* where) {
    PnrUnit u;
    u.lut4 = positive(o, "lut4", where);
    u.ff = positive(o, "ff", where);
    u.bram = o.value("bram", uint64_t{0});
    return u;
}
}  // namespace

PnrFigures parse_pnr(const std::string& text) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const std::exception& e) {
        throw std::runtime_error(std::string("place-and-route figures: not JSON: ") + e.what());
    }
    PnrFigures f;
    try {
        f.technology = j.at("technology").get<std::string>();
        f.package = j.at("package").get<std::string>();
        f.tool = j.at("tools").at("nextpnr").get<std::string>();
        const nlohmann::json& c = j.at("configuration");
        f.configuration = c.at("text").get<std::string>();
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(std::string("place-and-route figures: ") + e.what());
    }
    if (f.technology.empty()) throw std::runtime_error("place-and-route figures: no technology");
    const nlohmann::json& pe = j.contains("pe") ? j["pe"] : nlohmann::json::object();
    f.pe = unit(pe, "pe");
    f.logic_cells = positive(pe, "logic_cells", "pe");
    f.logic_cells_available = positive(pe, "logic_cells_available", "pe");
    if (!pe.contains("fmax_mhz") || !pe["fmax_mhz"].is_number() ||
        !(pe["fmax_mhz"].get<double>() > 0))
        throw std::runtime_error("place-and-route figures: pe.fmax_mhz missing or not positive");
    f.fmax_mhz = pe["fmax_mhz"].get<double>();
    const nlohmann::json& cp = j.contains("cp") ? j["cp"] : nlohmann::json::object();
    f.cp = unit(cp, "cp");
    f.cp_fits = cp.value("fits", false);
    f.pe1k = unit(j.contains("pe_1k") ? j["pe_1k"] : nlohmann::json::object(), "pe_1k");
    f.hdl_sha256 = j.value("hdl_sha256", std::string());
    if (j.contains("chip")) {
        f.chip = unit(j["chip"], "chip");
        f.chip_fits = j["chip"].value("fits", false);
    }
    f.available = true;
    return f;
}

const PnrFigures& place_and_route() {
    static const PnrFigures f = [] {
        const auto& files = detail::pnr::embedded_sources();
        const char* t = files.empty() ? "" : files.front().second;
        return *t ? parse_pnr(t) : PnrFigures{};
    }();
    return f;
}

std::string design_sha256() {
    std::vector<std::pair<std::string, std::string>> files;
    for (const auto& [path, text] : detail::embedded_sources())
        if (std::string(path).rfind("hdl/", 0) == 0) files.emplace_back(path, text);
    std::sort(files.begin(), files.end());
    detail::Sha256 h;
    for (const auto& [path, text] : files) {
        h.update("file " + path + " " + std::to_string(text.size()) + "\n");
        h.update(text);
    }
    return h.hex();
}

bool above_fmax(const PnrFigures& f, double clock_mhz) {
    return f.available && clock_mhz > f.fmax_mhz;
}

std::string fmax_text(const PnrFigures& f, double clock_mhz) {
    if (!f.available) return "";
    char b[512];
    std::snprintf(b, sizeof b,
                  "design Fmax: %s%.2f MHz on %s (nextpnr-ice40, %s, docs/rtl.md); the %g MHz "
                  "clock is %s it",
                  f.cp_fits ? "" : "at most ", f.fmax_mhz, f.technology.c_str(),
                  f.configuration.c_str(), clock_mhz,
                  above_fmax(f, clock_mhz) ? "above" : "within");
    return b;
}

}  // namespace imap::rtl
