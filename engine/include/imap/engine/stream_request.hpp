// The request of `imapsim stream` as its flags give it: checking the flags
// (ranges, combinations, output paths; the messages imapsim prints), opening
// the source and planning the firmware into the testbench's setup, and the
// head of the per-frame log. Running the stream is stream.hpp's.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "imap/engine/flag_values.hpp"
#include "imap/engine/stream.hpp"

namespace imap::engine::stream {

// The flags of imapsim stream, as given (numbers as text: checked here).
struct Request {
    std::string frames_dir, left_video, right_video, synthetic, calib;
    std::string fps = "25", deadline_ms, line_us;
    std::string out_dir, video, json_log, csv_log, max_frames;
    std::string seed = "1", size = "128x128";
    std::string quantum_ns;
    bool out_color = false, fail_on_deadline = false;
    AlgoSettings algo;
    MachineSettings machine;
};

// The checked request: the opened source, the testbench's setup (the
// planned firmware, machine, TLM and camera timing) and the outputs.
struct Prepared {
    OpenedSource opened;
    testbench::StreamSetup setup;
    Outputs outputs;  // json / csv default to OUT-DIR/stream.json, stream.csv
};

// Checks the flags and the output paths (engine::Error, exit 2; nothing is
// created), opens the source and plans the firmware.
Prepared prepare(const Request& r);

// The head of the per-frame log: source, calibration, size, ROI,
// parameters, machine, timing and model.
nlohmann::json log_head(const Request& r, const Prepared& pr);

}  // namespace imap::engine::stream
