#include "imap/tlm/components.hpp"

#include <algorithm>
#include <climits>
#include <cstring>
#include <stdexcept>

namespace imap::tlm {

namespace {

// A memory region of a target: `size` bytes of modeled address space at
// `base` in the target's map.
struct Region {
    uint8_t* data = nullptr;
    uint64_t base = 0, size = 0;
};

// Finds the region holding [a, a + len) or returns false.
bool find(const Region* regions, int n, uint64_t a, uint64_t len, const Region** out) {
    for (int i = 0; i < n; ++i) {
        const Region& r = regions[i];
        if (r.size == 0 || a < r.base || a - r.base >= r.size) continue;
        if (len > r.size - (a - r.base)) return false;
        *out = &r;
        return true;
    }
    return false;
}

// Common checks of the generic payload; false (with the response set) when
// the transaction cannot be served.
bool plain(::tlm::tlm_generic_payload& tr, bool dbg) {
    if (!dbg && tr.get_byte_enable_ptr()) {
        tr.set_response_status(::tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
        return false;
    }
    if (!dbg && tr.get_streaming_width() < tr.get_data_length()) {
        tr.set_response_status(::tlm::TLM_BURST_ERROR_RESPONSE);
        return false;
    }
    return true;
}

// The external memory for a lookup, without telling the machine that the
// host writes it: the targets do that (Machine::ext_data(), after which
// the machine clears all of it on reset) only for a write into it or a DMI
// pointer to it, so reads and local-memory traffic keep the cheap reset.
uint8_t* ext_view(isa::Machine& m) {
    return const_cast<uint8_t*>(static_cast<const isa::Machine&>(m).ext_data());
}

}  // namespace

// ---------------------------------------------------------------------------
// Pe

Pe::Pe(sc_core::sc_module_name name, int index, isa::Machine& m, sc_core::sc_time period)
    : sc_module(name), socket("socket"), index_(index), m_(m), period_(period) {
    socket.register_b_transport(this, &Pe::b_transport);
    socket.register_transport_dbg(this, &Pe::transport_dbg);
    socket.register_get_direct_mem_ptr(this, &Pe::get_direct_mem_ptr);
}

unsigned Pe::access(::tlm::tlm_generic_payload& tr) {
    const size_t P = static_cast<size_t>(m_.pes());
    const isa::MachineConfig& c = m_.config();
    const Region regions[2] = {{m_.mem_data(), 0, c.mem_bytes},
                               {ext_view(m_), kPeExtBase, c.ext_bytes}};
    const uint64_t len = tr.get_data_length();
    const Region* r = nullptr;
    if (!find(regions, 2, tr.get_address(), len, &r)) {
        tr.set_response_status(::tlm::TLM_ADDRESS_ERROR_RESPONSE);
        return 0;
    }
    if (r == &regions[1] && tr.is_write()) m_.ext_data();
    // PE `index` owns every P-th byte of the address-major block.
    uint8_t* cell = r->data + (tr.get_address() - r->base) * P + static_cast<size_t>(index_);
    uint8_t* data = tr.get_data_ptr();
    if (tr.is_read()) {
        for (uint64_t i = 0; i < len; ++i) data[i] = cell[i * P];
    } else if (tr.is_write()) {
        for (uint64_t i = 0; i < len; ++i) cell[i * P] = data[i];
    }
    tr.set_response_status(::tlm::TLM_OK_RESPONSE);
    return static_cast<unsigned>(len);
}

void Pe::b_transport(::tlm::tlm_generic_payload& tr, sc_core::sc_time& delay) {
    tr.set_dmi_allowed(false);
    if (!plain(tr, false)) return;
    const unsigned n = access(tr);
    delay += period_ * static_cast<double>(n);
}

unsigned Pe::transport_dbg(::tlm::tlm_generic_payload& tr) {
    return access(tr);
}

// A PE's bytes are strided by P in the address-major storage, so there is no
// contiguous block to hand out: DMI is refused for the whole PE address space
// (top.array.mem grants it for the array block instead).
bool Pe::get_direct_mem_ptr(::tlm::tlm_generic_payload&, ::tlm::tlm_dmi& dmi) {
    dmi.allow_none();
    dmi.set_start_address(0);
    dmi.set_end_address(~sc_dt::uint64{0});
    return false;
}

// ---------------------------------------------------------------------------
// ArrayMem

ArrayMem::ArrayMem(sc_core::sc_module_name name, isa::Machine& m, sc_core::sc_time period)
    : sc_module(name), socket("socket"), m_(m), period_(period) {
    socket.register_b_transport(this, &ArrayMem::b_transport);
    socket.register_transport_dbg(this, &ArrayMem::transport_dbg);
    socket.register_get_direct_mem_ptr(this, &ArrayMem::get_direct_mem_ptr);
}

unsigned ArrayMem::access(::tlm::tlm_generic_payload& tr) {
    const uint64_t P = static_cast<uint64_t>(m_.pes());
    const isa::MachineConfig& c = m_.config();
    const Region regions[2] = {{m_.mem_data(), 0, uint64_t{c.mem_bytes} * P},
                               {ext_view(m_), kArrayExtBase, uint64_t{c.ext_bytes} * P}};
    const uint64_t len = tr.get_data_length();
    const Region* r = nullptr;
    if (!find(regions, 2, tr.get_address(), len, &r)) {
        tr.set_response_status(::tlm::TLM_ADDRESS_ERROR_RESPONSE);
        return 0;
    }
    if (r == &regions[1] && tr.is_write()) m_.ext_data();
    uint8_t* p = r->data + (tr.get_address() - r->base);
    if (tr.is_read())
        std::memcpy(tr.get_data_ptr(), p, len);
    else if (tr.is_write())
        std::memcpy(p, tr.get_data_ptr(), len);
    tr.set_response_status(::tlm::TLM_OK_RESPONSE);
    return static_cast<unsigned>(len);
}

void ArrayMem::b_transport(int, ::tlm::tlm_generic_payload& tr, sc_core::sc_time& delay) {
    if (!plain(tr, false)) return;
    const unsigned n = access(tr);
    const uint64_t P = static_cast<uint64_t>(m_.pes());
    delay += period_ * static_cast<double>((n + P - 1) / P);  // one row per period
    tr.set_dmi_allowed(n > 0);
}

unsigned ArrayMem::transport_dbg(int, ::tlm::tlm_generic_payload& tr) {
    return access(tr);
}

bool ArrayMem::get_direct_mem_ptr(int, ::tlm::tlm_generic_payload& tr, ::tlm::tlm_dmi& dmi) {
    const uint64_t P = static_cast<uint64_t>(m_.pes());
    const isa::MachineConfig& c = m_.config();
    const Region regions[2] = {{m_.mem_data(), 0, uint64_t{c.mem_bytes} * P},
                               {ext_view(m_), kArrayExtBase, uint64_t{c.ext_bytes} * P}};
    const Region* r = nullptr;
    if (!find(regions, 2, tr.get_address(), 1, &r)) {
        dmi.allow_none();
        return false;
    }
    // A writable pointer into the external memory: the machine then clears
    // all of it on reset (Machine::ext_data).
    if (r == &regions[1]) m_.ext_data();
    dmi.set_dmi_ptr(r->data);
    dmi.set_start_address(r->base);
    dmi.set_end_address(r->base + r->size - 1);
    dmi.allow_read_write();
    dmi.set_read_latency(period_);
    dmi.set_write_latency(period_);
    ++dmi_grants_;
    return true;
}

// ---------------------------------------------------------------------------
// Array

Array::Array(sc_core::sc_module_name name, isa::Machine& m, sc_core::sc_time period)
    : sc_module(name), pe("pe"), mem("mem", m, period) {
    pe.init(static_cast<size_t>(m.pes()),
            [&](const char* n, size_t i) { return new Pe(n, static_cast<int>(i), m, period); });
}

// ---------------------------------------------------------------------------
// Ring, MaskBus

Ring::Ring(sc_core::sc_module_name name, int pes)
    : sc_module(name), scratch_(static_cast<size_t>(pes)) {}

namespace {
[[noreturn, gnu::cold, gnu::noinline]] void ring_size_mismatch(const char* name, size_t built,
                                                               int driven) {
    throw std::logic_error(std::string(name) + ": built for " + std::to_string(built) +
                           " PEs, driven with " + std::to_string(driven));
}
}  // namespace

void Ring::shift(uint8_t* dst, const uint8_t* src, const uint8_t* mask, int P, int hops,
                 bool towards_higher) {
    const size_t n = scratch_.size();
    if (static_cast<size_t>(P) != n) ring_size_mismatch(name(), n, P);
    uint8_t* links = scratch_.data();
    if (towards_higher) {
        isa::ring_shift<true>(dst, src, mask, links, n, static_cast<size_t>(hops));
        ++stats_.left;
    } else {
        isa::ring_shift<false>(dst, src, mask, links, n, static_cast<size_t>(hops));
        ++stats_.right;
    }
    ++stats_.transfers;
    stats_.hops += static_cast<uint64_t>(hops);
}

MaskBus::MaskBus(sc_core::sc_module_name name) : sc_module(name) {}

uint32_t MaskBus::reduce(const uint8_t* t, const uint8_t* mask, int P, bool any) {
    const uint32_t r = isa::status_reduce(t, mask, static_cast<size_t>(P), any);
    ++stats_.reductions;
    ++(any ? stats_.any : stats_.all);
    stats_.true_results += r;
    return r;
}

// ---------------------------------------------------------------------------
// VideoSource

VideoSource::VideoSource(sc_core::sc_module_name name) : sc_module(name), socket("socket") {
    socket.register_b_transport(this, &VideoSource::b_transport);
    socket.register_transport_dbg(this, &VideoSource::transport_dbg);
}

namespace {
void check_port(int port) {
    if (port < 0 || port > 1)
        throw std::out_of_range("video port " + std::to_string(port) + " does not exist (0, 1)");
}
}  // namespace

void VideoSource::set_input(int port, Image img) {
    check_port(port);
    if (img.width < 0 || img.height < 0 ||
        img.pixels.size() != static_cast<size_t>(img.width) * static_cast<size_t>(img.height))
        throw std::invalid_argument("video input " + std::to_string(port) + ": " +
                                    std::to_string(img.pixels.size()) + " pixels for " +
                                    std::to_string(img.width) + "x" + std::to_string(img.height));
    images_.input[port] = std::move(img);
}

void VideoSource::make_output(int port, int width, int height) {
    check_port(port);
    if (width < 0 || height < 0)
        throw std::invalid_argument("video output " + std::to_string(port) + ": size " +
                                    std::to_string(width) + "x" + std::to_string(height));
    images_.make_output(port, width, height);
}

const VideoSource::Image& VideoSource::input(int port) const {
    check_port(port);
    return images_.input[port];
}

const VideoSource::Image& VideoSource::output(int port) const {
    check_port(port);
    return images_.output[port];
}

bool VideoSource::transfer(::tlm::tlm_generic_payload& tr, bool debug) {
    VideoLine* line = nullptr;
    tr.get_extension(line);
    if (!line) {
        tr.set_response_status(::tlm::TLM_GENERIC_ERROR_RESPONSE);
        return false;
    }
    if (!plain(tr, false)) {
        line->error = "unsupported transaction (byte enables or streaming)";
        return false;
    }
    const int port = static_cast<int>(std::min<sc_dt::uint64>(tr.get_address(), INT_MAX));
    const int n = static_cast<int>(tr.get_data_length());
    if (stream_ && debug) {
        line->error = "debug access to a streamed video path";
        tr.set_response_status(::tlm::TLM_COMMAND_ERROR_RESPONSE);
        return false;
    }
    try {
        isa::VideoPort* const path = stream_ ? stream_ : &images_;
        if (tr.is_read())
            path->read_line(port, line->y, line->x0, tr.get_data_ptr(), n);
        else if (tr.is_write())
            path->write_line(port, line->y, line->x0, tr.get_data_ptr(), n);
    } catch (const std::exception& e) {
        line->error = e.what();
        tr.set_response_status(::tlm::TLM_ADDRESS_ERROR_RESPONSE);
        return false;
    }
    tr.set_response_status(::tlm::TLM_OK_RESPONSE);
    return true;
}

void VideoSource::b_transport(::tlm::tlm_generic_payload& tr, sc_core::sc_time&) {
    // No delay annotated [A]: see the class comment. A streamed path may
    // wait() for a line that has not arrived yet (the CP stalls).
    if (!transfer(tr, false)) {
        ++stats_.errors;
        return;
    }
    if (tr.is_read()) ++stats_.lines_in;
    if (tr.is_write()) ++stats_.lines_out;
}

unsigned VideoSource::transport_dbg(::tlm::tlm_generic_payload& tr) {
    return transfer(tr, true) ? tr.get_data_length() : 0;
}

}  // namespace imap::tlm
