// The passive components of the TLM model: the PE array (one sc_module per
// PE with a debug / video target socket on its local memory, plus the
// array-level memory target that grants DMI), the shift ring, the mask bus,
// and the host's video source. None of them has a SystemC process: the CP
// (cp.hpp) is the only active component.
#pragma once

#include <tlm_utils/multi_passthrough_target_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <cstdint>
#include <memory>
#include <string>
#include <systemc>
#include <tlm>
#include <vector>

#include "imap/isa/machine.hpp"

namespace imap::tlm {

// ---------------------------------------------------------------------------
// Address maps
//
// PE socket (top.array.pe_<i>.socket), the memories of PE i:
//   [0, mem_bytes)                          local memory, address = addr
//   [kPeExtBase, kPeExtBase + ext_bytes)    external memory, address - kPeExtBase
// Array memory (top.array.mem.socket), the address-major blocks as stored:
//   [0, mem_bytes * P)                      local memory, address = addr * P + pe
//   [kArrayExtBase, + ext_bytes * P)        external memory, same layout
// A broadcast-address row (one video line) is P contiguous bytes of the array
// space; a PE's own memory is strided by P, hence DMI only at array level.
inline constexpr uint64_t kPeExtBase = 0x1000'0000ull;
inline constexpr uint64_t kArrayExtBase = 0x1'0000'0000ull;

// b_transport delay of a host access to PE memory [A]: one clock period per
// byte per PE port (the array-level target moves one row of P bytes per
// period). transport_dbg is untimed; DMI reports the same latencies.

// ---------------------------------------------------------------------------
// One PE: a view on lane `index` of the machine's state (no copy of it).
class Pe : public sc_core::sc_module {
  public:
    // Optional binding: a testbench binds only the PEs it talks to.
    tlm_utils::simple_target_socket_optional<Pe> socket;

    Pe(sc_core::sc_module_name name, int index, isa::Machine& m, sc_core::sc_time period);
    const char* kind() const override { return "imap::tlm::Pe"; }

    int index() const { return index_; }
    uint8_t reg(int r) const { return m_.reg(index_, r); }
    uint8_t mem(uint32_t addr) const { return m_.mem_read(index_, addr); }
    bool carry() const { return m_.carry_lanes()[index_] != 0; }
    bool test() const { return m_.test_lanes()[index_] != 0; }
    bool active() const { return m_.mask_lanes()[index_] != 0; }

  private:
    void b_transport(::tlm::tlm_generic_payload& tr, sc_core::sc_time& delay);
    unsigned transport_dbg(::tlm::tlm_generic_payload& tr);
    bool get_direct_mem_ptr(::tlm::tlm_generic_payload& tr, ::tlm::tlm_dmi& dmi);
    unsigned access(::tlm::tlm_generic_payload& tr);  // sets the response status

    int index_;
    isa::Machine& m_;
    sc_core::sc_time period_;
};

// The array's memories as one target in address-major order (grants DMI).
class ArrayMem : public sc_core::sc_module {
  public:
    tlm_utils::multi_passthrough_target_socket_optional<ArrayMem> socket;

    ArrayMem(sc_core::sc_module_name name, isa::Machine& m, sc_core::sc_time period);
    const char* kind() const override { return "imap::tlm::ArrayMem"; }

    uint64_t dmi_grants() const { return dmi_grants_; }

  private:
    void b_transport(int id, ::tlm::tlm_generic_payload& tr, sc_core::sc_time& delay);
    unsigned transport_dbg(int id, ::tlm::tlm_generic_payload& tr);
    bool get_direct_mem_ptr(int id, ::tlm::tlm_generic_payload& tr, ::tlm::tlm_dmi& dmi);
    unsigned access(::tlm::tlm_generic_payload& tr);

    isa::Machine& m_;
    sc_core::sc_time period_;
    uint64_t dmi_grants_ = 0;
};

// top.array: P PE modules top.array.pe_0 .. pe_<P-1> (P from the runtime
// configuration) and the array memory target top.array.mem.
class Array : public sc_core::sc_module {
  public:
    Array(sc_core::sc_module_name name, isa::Machine& m, sc_core::sc_time period);
    const char* kind() const override { return "imap::tlm::Array"; }

    int size() const { return static_cast<int>(pe.size()); }
    sc_core::sc_vector<Pe> pe;  // elements named pe_<i>
    ArrayMem mem;
};

// ---------------------------------------------------------------------------
// top.ring: the shift ring, attached to the machine as its isa::RingPort.
struct RingStats {
    uint64_t transfers = 0;   // rxl + rxr instructions
    uint64_t left = 0;        // rxl (data towards higher PE indices)
    uint64_t right = 0;       // rxr
    uint64_t hops = 0;        // sum of k (one hop = one ring_hop cost)
    uint64_t lane_bytes = 0;  // bytes moved over PE-to-PE links: hops * P
};

class Ring : public sc_core::sc_module, public isa::RingPort {
  public:
    Ring(sc_core::sc_module_name name, int pes);
    const char* kind() const override { return "imap::tlm::Ring"; }
    void shift(uint8_t* dst, const uint8_t* src, const uint8_t* mask, int P, int hops,
               bool towards_higher) override;
    RingStats stats() const {
        RingStats s = stats_;
        s.lane_bytes = s.hops * scratch_.size();
        return s;
    }

  private:
    std::vector<uint8_t> scratch_;  // the values on the ring links
    RingStats stats_;
};

// top.maskbus: the mask bus with the status reduction (rany / rall),
// attached as the machine's isa::StatusPort.
struct MaskBusStats {
    uint64_t reductions = 0;     // rany + rall
    uint64_t any = 0;            // rany
    uint64_t all = 0;            // rall
    uint64_t true_results = 0;   // reductions that returned 1
    uint64_t mask_commands = 0;  // mif / melse / mend / mall (from the machine's counters)
};

class MaskBus : public sc_core::sc_module, public isa::StatusPort {
  public:
    explicit MaskBus(sc_core::sc_module_name name);
    const char* kind() const override { return "imap::tlm::MaskBus"; }
    uint32_t reduce(const uint8_t* t, const uint8_t* mask, int P, bool any) override;
    const MaskBusStats& stats() const { return stats_; }

  private:
    MaskBusStats stats_;
};

// ---------------------------------------------------------------------------
// Video line transactions (top.cp.video -> top.video).
//
// A generic payload whose address is the video port (0 = left / output 0,
// 1 = right / output 1) with the VideoLine extension (required): READ = input
// line `y` from column x0 (n = data length bytes, pixels outside the width
// read 0); WRITE = output line (pixels outside the width are dropped). On
// failure the target sets an error response and VideoLine::error.
struct VideoLine : public ::tlm::tlm_extension<VideoLine> {
    int y = 0, x0 = 0;
    std::string error;
    ::tlm::tlm_extension_base* clone() const override { return new VideoLine(*this); }
    void copy_from(const ::tlm::tlm_extension_base& e) override {
        *this = static_cast<const VideoLine&>(e);
    }
};

struct VideoStats {
    uint64_t lines_in = 0;   // successful input line reads
    uint64_t lines_out = 0;  // successful output line writes
    uint64_t errors = 0;     // refused transactions
};

// top.video: the host side of the video path (the testbench's images). Line
// semantics are isa::ImageVideoPort's; it annotates no delay [A]: the line is
// already waiting in the board's video line buffer, and moving it into a
// memory row is the video_line cost the machine charges.
class VideoSource : public sc_core::sc_module {
  public:
    tlm_utils::simple_target_socket<VideoSource> socket;

    explicit VideoSource(sc_core::sc_module_name name);
    const char* kind() const override { return "imap::tlm::VideoSource"; }

    using Image = isa::ImageVideoPort::Image;
    void set_input(int port, Image img);
    void make_output(int port, int width, int height);
    const Image& input(int port) const;
    const Image& output(int port) const;
    const VideoStats& stats() const { return stats_; }
    // Routes line transfers to a streamed video path (the streaming
    // testbench, testbench/) instead of the host images; nullptr = host
    // images again. Its read_line runs in the CP's thread inside b_transport
    // and may wait() until line y has arrived (the CP stalls); exceptions
    // become the transaction's VideoLine::error. Debug transactions are
    // refused while a stream is attached.
    void attach_stream(isa::VideoPort* s) { stream_ = s; }

  private:
    void b_transport(::tlm::tlm_generic_payload& tr, sc_core::sc_time& delay);
    unsigned transport_dbg(::tlm::tlm_generic_payload& tr);
    bool transfer(::tlm::tlm_generic_payload& tr, bool debug);

    isa::ImageVideoPort images_;
    isa::VideoPort* stream_ = nullptr;
    VideoStats stats_;
};

}  // namespace imap::tlm
