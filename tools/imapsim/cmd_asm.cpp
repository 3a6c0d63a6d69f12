// imapsim asm / disasm: the firmware assembler and disassembler (docs/isa.md).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>

#include "asm_flags.hpp"
#include "cli_common.hpp"
#include "imap/isa/assembler.hpp"
#include "imap/isa/program.hpp"

namespace imapsim {

namespace isa = imap::isa;

isa::AsmOptions asm_options(const std::vector<std::string>& defines) {
    isa::AsmOptions opt;
    for (const std::string& d : defines) {
        std::pair<std::string, int64_t> def;
        try {
            def = isa::parse_define(d);
        } catch (const std::invalid_argument& e) {
            throw UserError(e.what());
        }
        if (opt.defines.count(def.first))
            throw UserError("-D " + def.first + " given more than once");
        opt.defines.insert(def);
    }
    return opt;
}

isa::Program assemble_or_report(const std::string& src, const isa::AsmOptions& opt,
                                const std::string& outcome) {
    try {
        return isa::assemble_file(src, opt);
    } catch (const isa::AsmError& e) {
        const auto& ds = e.diagnostics();
        if (ds.size() == 1 && ds[0].line == 0) throw UserError(ds[0].message);  // unreadable
        for (const isa::Diagnostic& d : ds) std::cerr << d.str() << "\n";
        size_t n = 0;
        for (const isa::Diagnostic& d : ds) n += d.message.rfind("too many errors", 0) != 0;
        throw UserError(src + " does not assemble (" + std::to_string(n) + " error" +
                        (n == 1 ? "" : "s") + "); " + outcome);
    }
}

namespace {

struct AsmCliOptions {
    std::string src, out, listing;
    std::vector<std::string> defines;
    bool no_source_map = false;
};

struct DisasmCliOptions {
    std::string bin, out;
    bool no_comments = false;
};

// Writes text to `path` through a temporary file and a rename, so that a
// failure never leaves a half-written file behind.
void write_text_atomic(const std::string& path, const std::string& text, const char* what) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        if (!f)
            throw UserError(std::string("cannot write ") + what + " '" + path +
                            "': " + std::strerror(errno));
        f << text;
        f.flush();
        if (!f) {
            std::remove(tmp.c_str());
            throw UserError(std::string("cannot write ") + what + " '" + path + "'");
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string err = std::strerror(errno);
        std::remove(tmp.c_str());
        throw UserError(std::string("cannot write ") + what + " '" + path + "': " + err);
    }
}

}  // namespace

Subcommand register_asm(CLI::App& app) {
    auto o = std::make_shared<AsmCliOptions>();
    CLI::App* sub = app.add_subcommand(
        "asm", "Assemble IMAP-VISION firmware into a program file (IMAPFW01, docs/isa.md)");
    sub->add_option("SRC", o->src, "assembler source file")->required();
    sub->add_option("-o,--out", o->out, "output program file")->required();
    sub->add_option("-D,--define", o->defines,
                    "define a constant NAME=VALUE (or NAME, = 1) before the source; repeatable")
        ->allow_extra_args(false);
    sub->add_flag("--no-source-map", o->no_source_map,
                  "leave the PC -> file:line map out of the program file");
    sub->add_option("--listing", o->listing, "also write a disassembly listing to this file");

    return {sub, [o]() {
                check_output_file("--out", o->out, false);  // both before anything is written
                check_output_file("--listing", o->listing, false);
                isa::AsmOptions opt = asm_options(o->defines);
                opt.source_map = !o->no_source_map;
                const isa::Program p = assemble_or_report(o->src, opt, "nothing written");
                try {
                    isa::save_program(p, o->out, !o->no_source_map);
                } catch (const isa::FormatError& e) {
                    throw UserError(e.what());
                }
                if (!o->listing.empty())
                    write_text_atomic(o->listing, isa::disassemble(p), "listing");
                std::printf("asm: %s -> %s: %zu instructions, %zu phases, %zu labels\n",
                            o->src.c_str(), o->out.c_str(), p.code.size(), p.phases.size(),
                            p.symbols.size());
                return static_cast<int>(kExitOk);
            }};
}

Subcommand register_disasm(CLI::App& app) {
    auto o = std::make_shared<DisasmCliOptions>();
    CLI::App* sub = app.add_subcommand(
        "disasm", "Disassemble a program file; the output re-assembles to the same code");
    sub->add_option("BIN", o->bin, "program file (IMAPFW01)")->required();
    sub->add_option("-o,--out", o->out, "write the text here instead of standard output");
    sub->add_flag("--no-comments", o->no_comments, "leave out the PC / source comments");

    return {sub, [o]() {
                check_output_file("--out", o->out, false);
                isa::Program p;
                try {
                    p = isa::load_program(o->bin);
                } catch (const isa::FormatError& e) {
                    throw UserError(e.what());
                }
                isa::DisasmOptions opt;
                opt.comments = !o->no_comments;
                const std::string text = isa::disassemble(p, opt);
                if (o->out.empty()) {
                    std::fwrite(text.data(), 1, text.size(), stdout);
                } else {
                    write_text_atomic(o->out, text, "disassembly");
                }
                return static_cast<int>(kExitOk);
            }};
}

}  // namespace imapsim
