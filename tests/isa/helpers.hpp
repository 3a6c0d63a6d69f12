// Small helpers shared by the imap_isa tests.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "imap/isa/isa.hpp"

namespace isatest {

using namespace imap::isa;

inline MachineConfig small(int pes = 4) {
    MachineConfig c;
    c.pes = pes;
    c.mem_bytes = 1024;
    c.ext_bytes = 256;
    c.watchdog_cycles = 1000000;
    return c;
}

// Assembles `src`, loads it, lets `setup` poke inputs, runs to halt.
inline std::unique_ptr<Machine> run(const std::string& src, const MachineConfig& cfg = small(),
                                    const std::function<void(Machine&)>& setup = {}) {
    auto m = std::make_unique<Machine>(cfg);
    m->load(assemble_string(src, "t.s"));
    if (setup) setup(*m);
    m->run();
    return m;
}

inline std::vector<int> lanes(const Machine& m, int r) {
    std::vector<int> v;
    for (int p = 0; p < m.pes(); ++p) v.push_back(m.reg(p, r));
    return v;
}
inline std::vector<int> flags(const uint8_t* f, int P) {
    return std::vector<int>(f, f + P);
}

}  // namespace isatest
