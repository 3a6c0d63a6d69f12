// The IMAPFW01 binary format: round trips, rejection of bad and truncated
// files; and the docs table covering every opcode.
#define BOOST_TEST_MODULE isa_program
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "helpers.hpp"

using namespace isatest;
namespace fs = std::filesystem;

namespace {
Program sample() {
    return assemble_string(R"(
        .phase io
        cli c0, #3
    l:  add r1, r1, r2
        loop c0, l
        .phase compute
        halt)",
                           "sample.s");
}
std::string format_error(const std::vector<uint8_t>& b) {
    try {
        deserialize(b, "p.bin");
    } catch (const FormatError& e) {
        return e.what();
    }
    return "accepted";
}
}  // namespace

BOOST_AUTO_TEST_CASE(serialize_round_trip) {
    const Program p = sample();
    BOOST_REQUIRE_EQUAL(p.source_map.size(), p.code.size());
    const std::vector<uint8_t> b = serialize(p);
    BOOST_CHECK(std::equal(b.begin(), b.begin() + 8, "IMAPFW01"));
    const Program q = deserialize(b, "p.bin");
    BOOST_CHECK(q == p);
    BOOST_CHECK_EQUAL(q.location(2), "sample.s:4");
    BOOST_CHECK_EQUAL(q.phase_name(2), "compute");
    BOOST_CHECK_EQUAL(q.phase_name(9), "#9");

    const Program r = deserialize(serialize(p, false), "p.bin");
    BOOST_CHECK(r.code == p.code);
    BOOST_CHECK(r.phases == p.phases);
    BOOST_CHECK(r.symbols == p.symbols);
    BOOST_CHECK(r.source_map.empty());
    BOOST_CHECK(r.files.empty());
    BOOST_CHECK_EQUAL(r.location(1), "");
}

BOOST_AUTO_TEST_CASE(file_round_trip_is_atomic) {
    const fs::path dir =
        fs::temp_directory_path() / ("imap_isa_prog_" + std::to_string(std::random_device{}()));
    fs::create_directories(dir);
    const std::string path = (dir / "fw.bin").string();
    const Program p = sample();
    save_program(p, path);
    BOOST_CHECK(load_program(path) == p);
    BOOST_CHECK(!fs::exists(path + ".tmp"));
    BOOST_CHECK_THROW(save_program(p, (dir / "no/such/dir/fw.bin").string()), FormatError);
    BOOST_CHECK_THROW(load_program((dir / "absent.bin").string()), FormatError);
    fs::remove_all(dir);
}

BOOST_AUTO_TEST_CASE(every_truncation_is_rejected_clearly) {
    const std::vector<uint8_t> b = serialize(sample());
    for (size_t n = 0; n < b.size(); ++n) {
        const std::vector<uint8_t> cut(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(n));
        const std::string e = format_error(cut);
        BOOST_REQUIRE_MESSAGE(e != "accepted", "prefix of " << n << " bytes accepted");
        BOOST_REQUIRE_MESSAGE(e.find("bad program file 'p.bin'") == 0, e);
    }
    // Mid-code truncation names the section.
    const std::vector<uint8_t> cut(b.begin(), b.begin() + 40);
    const std::string e = format_error(cut);
    BOOST_CHECK_MESSAGE(e.find("truncated") != std::string::npos, e);
    BOOST_CHECK_MESSAGE(e.find("code") != std::string::npos, e);
}

BOOST_AUTO_TEST_CASE(bad_files_are_rejected) {
    std::vector<uint8_t> b = serialize(sample());
    BOOST_CHECK(format_error({'h', 'e', 'l', 'l', 'o'}).find("not an IMAP-VISION program") !=
                std::string::npos);
    std::vector<uint8_t> v = b;
    v[8] = 2;  // version
    BOOST_CHECK(format_error(v).find("unsupported version 2") != std::string::npos);
    for (size_t i = 32; i < b.size(); i += 5) {
        std::vector<uint8_t> c = b;
        c[i] ^= 0x5A;
        BOOST_REQUIRE_MESSAGE(format_error(c) != "accepted",
                              "corruption at byte " << i << " accepted");
    }
    std::vector<uint8_t> extra = b;
    extra.insert(extra.end() - 4, 0);
    BOOST_CHECK(format_error(extra) != "accepted");
    std::vector<uint8_t> huge = b;
    huge[16] = 0xFF;  // code count
    huge[17] = 0xFF;
    huge[18] = 0xFF;
    BOOST_CHECK(format_error(huge) != "accepted");
}

BOOST_AUTO_TEST_CASE(docs_list_every_opcode) {
    std::ifstream f(std::string(IMAP_DOCS_DIR) + "/isa.md");
    BOOST_REQUIRE_MESSAGE(f, "docs/isa.md missing");
    std::stringstream s;
    s << f.rdbuf();
    const std::string doc = s.str();
    for (const OpInfo& i : all_ops()) {
        char code[8];
        std::snprintf(code, sizeof code, "0x%02X", static_cast<unsigned>(i.op));
        const std::string row = "| " + std::string(code) + " | `" + std::string(i.mnemonic) + "`";
        BOOST_CHECK_MESSAGE(doc.find(row) != std::string::npos,
                            "docs/isa.md lacks row '" << row << "'");
    }
    for (const ParamInfo& p : MachineConfig{}.list())
        BOOST_CHECK_MESSAGE(doc.find("`" + p.name + "`") != std::string::npos,
                            "docs/isa.md lacks parameter " << p.name);
}
