// (b) the module hierarchy for P = 8; (d) the PE target sockets
// (b_transport, transport_dbg, DMI refused) and the array memory target
// (DMI granted on the address-major block).
#define BOOST_TEST_MODULE tlm_sockets
#include <tlm_utils/simple_initiator_socket.h>
#include <boost/test/unit_test.hpp>

#include "tlm_test_util.hpp"

using namespace tlmtest;
using imap::tlm::kArrayExtBase;
using imap::tlm::kPeExtBase;

namespace {

// The testbench's host: talks to PE 5, PE 0 and the array memory.
struct Host : sc_core::sc_module {
    tlm_utils::simple_initiator_socket<Host> pe5{"pe5"}, pe0{"pe0"}, mem{"mem"};
    explicit Host(sc_core::sc_module_name n) : sc_module(n) {}
};

// A transaction on `s`; returns the response status, `delay` the annotation.
template <typename Socket>
::tlm::tlm_response_status xfer(Socket& s, bool write, uint64_t addr, uint8_t* data, unsigned n,
                                sc_core::sc_time* delay = nullptr, bool dbg = false,
                                unsigned* dbg_bytes = nullptr) {
    ::tlm::tlm_generic_payload t;
    t.set_command(write ? ::tlm::TLM_WRITE_COMMAND : ::tlm::TLM_READ_COMMAND);
    t.set_address(addr);
    t.set_data_ptr(data);
    t.set_data_length(n);
    t.set_streaming_width(n);
    t.set_response_status(::tlm::TLM_INCOMPLETE_RESPONSE);
    if (dbg) {
        const unsigned b = s->transport_dbg(t);
        if (dbg_bytes) *dbg_bytes = b;
        return ::tlm::TLM_OK_RESPONSE;
    }
    sc_core::sc_time d = sc_core::SC_ZERO_TIME;
    s->b_transport(t, d);
    if (delay) *delay = d;
    return t.get_response_status();
}

const char* kStore = R"(
        pidx r0, #0
        addi r1, r0, #40        ; PE p: 40 + p
        st r1, [#10]
        addi r2, r0, #200       ; PE p: 200 + p
        st r2, [#11]
        cli c1, #2
        cli c2, #3
        xst [#10], ext[c2], c1  ; ext[3..4] = mem[10..11]
        halt
)";

}  // namespace

BOOST_AUTO_TEST_CASE(hierarchy_and_sockets_p8) {
    const isa::MachineConfig cfg = config(8);
    itlm::TlmSystem top("top", cfg, isa::assemble_string(kStore, "store.s"));
    Host host("host");
    host.pe5.bind(top.array.pe[5].socket);
    host.pe0.bind(top.array.pe[0].socket);
    host.mem.bind(top.array.mem.socket);

    // (b) names
    for (const char* n :
         {"top", "top.cp", "top.cp.video", "top.cp.mem", "top.array", "top.array.mem",
          "top.array.mem.socket", "top.ring", "top.maskbus", "top.video", "top.video.socket",
          "top.array.pe_0", "top.array.pe_5", "top.array.pe_7", "top.array.pe_5.socket"}) {
        BOOST_TEST_CONTEXT(n) {
            BOOST_CHECK(sc_core::sc_find_object(n) != nullptr);
        }
    }
    BOOST_CHECK(sc_core::sc_find_object("top.array.pe_8") == nullptr);
    for (int p = 0; p < 8; ++p) {
        const std::string n = "top.array.pe_" + std::to_string(p);
        auto* pe = dynamic_cast<itlm::Pe*>(sc_core::sc_find_object(n.c_str()));
        BOOST_REQUIRE(pe);
        BOOST_CHECK_EQUAL(pe->index(), p);
        BOOST_CHECK_EQUAL(std::string(pe->kind()), "imap::tlm::Pe");
    }
    BOOST_CHECK(dynamic_cast<itlm::Ring*>(sc_core::sc_find_object("top.ring")));
    BOOST_CHECK(dynamic_cast<itlm::MaskBus*>(sc_core::sc_find_object("top.maskbus")));
    BOOST_CHECK(dynamic_cast<itlm::Cp*>(sc_core::sc_find_object("top.cp")));
    BOOST_CHECK_EQUAL(top.array.size(), 8);

    sc_core::sc_start();
    top.rethrow_if_faulted();
    BOOST_REQUIRE(top.machine().halted());
    const isa::Machine& m = top.machine();
    const sc_core::sc_time period(25, sc_core::SC_NS);

    // (d) PE 5: b_transport read of local memory 10..11, one period per byte.
    uint8_t b[4] = {};
    sc_core::sc_time delay;
    BOOST_CHECK_EQUAL(xfer(host.pe5, false, 10, b, 2, &delay), ::tlm::TLM_OK_RESPONSE);
    BOOST_CHECK_EQUAL(int{b[0]}, 45);
    BOOST_CHECK_EQUAL(int{b[1]}, 205);
    BOOST_CHECK(delay == 2 * period);
    // transport_dbg reads the same bytes; PE 0 sees its own.
    uint8_t d[2] = {};
    unsigned nb = 0;
    xfer(host.pe5, false, 10, d, 2, nullptr, true, &nb);
    BOOST_CHECK_EQUAL(nb, 2u);
    BOOST_CHECK_EQUAL(int{d[0]}, 45);
    BOOST_CHECK_EQUAL(int{d[1]}, 205);
    xfer(host.pe0, false, 10, d, 2, nullptr, true, &nb);
    BOOST_CHECK_EQUAL(int{d[0]}, 40);
    BOOST_CHECK_EQUAL(int{d[1]}, 200);
    // External memory through the PE socket.
    BOOST_CHECK_EQUAL(xfer(host.pe5, false, kPeExtBase + 3, b, 2), ::tlm::TLM_OK_RESPONSE);
    BOOST_CHECK_EQUAL(int{b[0]}, 45);
    BOOST_CHECK_EQUAL(int{b[1]}, 205);

    // Writes land in PE 5's column only.
    uint8_t w[3] = {1, 2, 3};
    BOOST_CHECK_EQUAL(xfer(host.pe5, true, 20, w, 3), ::tlm::TLM_OK_RESPONSE);
    for (int i = 0; i < 3; ++i) {
        BOOST_CHECK_EQUAL(int{m.mem_read(5, 20 + i)}, i + 1);
        BOOST_CHECK_EQUAL(int{m.mem_read(4, 20 + i)}, 0);
        BOOST_CHECK_EQUAL(int{m.mem_read(6, 20 + i)}, 0);
    }
    uint8_t w2[2] = {9, 8};
    xfer(host.pe0, true, 62, w2, 2, nullptr, true, &nb);  // debug write, last two bytes
    BOOST_CHECK_EQUAL(nb, 2u);
    BOOST_CHECK_EQUAL(int{m.mem_read(0, 62)}, 9);
    BOOST_CHECK_EQUAL(int{m.mem_read(0, 63)}, 8);

    // Out of range: address error, nothing touched; debug access returns 0 bytes.
    BOOST_CHECK_EQUAL(xfer(host.pe5, false, 63, b, 2), ::tlm::TLM_ADDRESS_ERROR_RESPONSE);
    BOOST_CHECK_EQUAL(xfer(host.pe5, false, 64, b, 1), ::tlm::TLM_ADDRESS_ERROR_RESPONSE);
    BOOST_CHECK_EQUAL(xfer(host.pe5, false, kPeExtBase + 32, b, 1),
                      ::tlm::TLM_ADDRESS_ERROR_RESPONSE);
    xfer(host.pe5, true, 64, w, 1, nullptr, true, &nb);
    BOOST_CHECK_EQUAL(nb, 0u);

    // A PE refuses DMI (its bytes are strided by P).
    {
        ::tlm::tlm_generic_payload t;
        t.set_address(10);
        t.set_command(::tlm::TLM_READ_COMMAND);
        ::tlm::tlm_dmi dmi;
        BOOST_CHECK(!host.pe5->get_direct_mem_ptr(t, dmi));
        BOOST_CHECK(dmi.is_none_allowed());
    }

    // The array memory grants DMI on the address-major block.
    {
        ::tlm::tlm_generic_payload t;
        t.set_address(0);
        t.set_command(::tlm::TLM_WRITE_COMMAND);
        ::tlm::tlm_dmi dmi;
        BOOST_REQUIRE(host.mem->get_direct_mem_ptr(t, dmi));
        BOOST_CHECK(dmi.is_read_write_allowed());
        BOOST_CHECK_EQUAL(dmi.get_start_address(), 0u);
        BOOST_CHECK_EQUAL(dmi.get_end_address(), 64u * 8u - 1u);
        BOOST_CHECK(dmi.get_dmi_ptr() == m.mem_data());
        BOOST_CHECK(dmi.get_read_latency() == period);
        // byte (pe, addr) at addr * P + pe: row 10 is 40..47
        for (int p = 0; p < 8; ++p) BOOST_CHECK_EQUAL(int{dmi.get_dmi_ptr()[10 * 8 + p]}, 40 + p);
        dmi.get_dmi_ptr()[30 * 8 + 5] = 77;  // write PE 5, address 30
        xfer(host.pe5, false, 30, d, 1, nullptr, true, &nb);
        BOOST_CHECK_EQUAL(int{d[0]}, 77);
        BOOST_CHECK_EQUAL(int{m.mem_read(5, 30)}, 77);
    }
    {
        ::tlm::tlm_generic_payload t;
        t.set_address(kArrayExtBase + 5);
        ::tlm::tlm_dmi dmi;
        BOOST_REQUIRE(host.mem->get_direct_mem_ptr(t, dmi));
        BOOST_CHECK_EQUAL(dmi.get_start_address(), kArrayExtBase);
        BOOST_CHECK_EQUAL(dmi.get_end_address(), kArrayExtBase + 32u * 8u - 1u);
        BOOST_CHECK(dmi.get_dmi_ptr() == m.ext_data());
        BOOST_CHECK_EQUAL(int{dmi.get_dmi_ptr()[3 * 8 + 2]}, 42);
        t.set_address(kArrayExtBase + 32u * 8u);
        BOOST_CHECK(!host.mem->get_direct_mem_ptr(t, dmi));
    }
    // One row through b_transport: P bytes in one period.
    uint8_t row[8] = {};
    BOOST_CHECK_EQUAL(xfer(host.mem, false, 11 * 8, row, 8, &delay), ::tlm::TLM_OK_RESPONSE);
    for (int p = 0; p < 8; ++p) BOOST_CHECK_EQUAL(int{row[p]}, 200 + p);
    BOOST_CHECK(delay == period);
    BOOST_CHECK(top.cp.used_dmi());
    BOOST_CHECK_GE(top.array.mem.dmi_grants(), 1u);
}
