// Machine, cost and algorithm parameters as JSON: one form for every report
// (the run report, exec, eval, the sweep's fixed parameters).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "imap/golden/params.hpp"
#include "imap/isa/config.hpp"

namespace imap::engine {

// One machine parameter's value as JSON: a number (integer or real), or a
// boolean for an on/off switch (isa::ParamInfo::value is text).
nlohmann::json param_value_json(const isa::ParamInfo& p);
// Every machine and cost parameter of `cfg`, name -> value (param_value_json).
nlohmann::json machine_params_json(const isa::MachineConfig& cfg);
// Per parameter: {"assumption": bool, "faster": bool, "unit", "group"}
// (docs/isa.md 2.2: an assumption is [A], one that makes the machine faster
// than the published facts [A+]).
nlohmann::json machine_param_info_json(const isa::MachineConfig& cfg);

// The algorithm parameters as a JSON object (reports); the SPEC A.9
// options only when the parameters use them.
nlohmann::json algo_params_json(const golden::Params& p);
// The [A+] parameters as "name value unit" items joined by ", ".
std::string faster_assumptions_text(const isa::MachineConfig& cfg);

}  // namespace imap::engine
