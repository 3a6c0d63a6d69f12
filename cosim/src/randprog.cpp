// The constrained-random program generator's entry (generate_program): from
// a seed and GenOptions, a program's machine configuration (a random cost
// table and board timing), its video images and parameters, a prologue of
// random CP and PE values, GenOptions::blocks top-level blocks
// (randprog_control.cpp and the files it draws from), an ending (halt or
// one of the deliberate machine faults of Gen::fault_ending) and the
// subroutines the calls reach.
#include <algorithm>

#include "model.hpp"
#include "randprog_gen.hpp"

namespace imap::rtl {

namespace randgen {

void Gen::fault_ending() {
    switch (u(9)) {
        case 0:
            out_.ending = "ld out of range";
            emit(enc(LD, 0, 0, 128, o_.mem_bytes + static_cast<uint32_t>(u(5))));
            break;
        case 1: {
            out_.ending = "ldx out of range on some PEs";
            const int lo = NR_ - 2;
            emit(enc(PIDX, static_cast<uint32_t>(lo)));
            emit(enc(LDX, 0, static_cast<uint32_t>(lo), 0,
                     (1u << 29) | ((o_.mem_bytes - 2) & 0xffffff)));
            break;
        }
        case 2:
            out_.ending = "mask stack overflow";
            for (int i = 0; i <= out_.cfg.mask_depth; ++i) emit(enc(MIF));
            break;
        case 3:
            out_.ending = "ret without call";
            emit(enc(RET));
            break;
        case 4:
            out_.ending = "cld out of range";
            emit(enc(CLD, 0, 0, 128, 256 + static_cast<uint32_t>(u(10))));
            break;
        case 5:
            out_.ending = "negative transfer length";
            set_base(kBase0 + 2, 0xffffffffu);
            emit(enc(XLD, kBase0 + 2, kBase0 + 1, 128, 0));
            break;
        case 6:
            out_.ending = "video line outside the image";
            set_base(0, static_cast<uint32_t>(out_.left.height));
            emit(enc(VIN, 0, 0, 128, 0));
            break;
        case 7: {
            out_.ending = "watchdog";
            out_.cfg.watchdog_cycles = 200 + u(2000);
            const uint32_t top = static_cast<uint32_t>(here());
            emit(enc(ADD, 1, 1, 2));
            emit(enc(JMP, 0, 0, 0, top));
            break;
        }
        default:
            out_.ending = "mend on an empty stack";
            emit(enc(MALL));
            emit(enc(MEND));
            break;
    }
}

void Gen::strap_sweep() {
    isa::MachineConfig& cfg = out_.cfg;
    // consecutive seeds take consecutive values of each list: every bit that
    // differs between neighbours toggles (the 20-bit patterns cover the cost
    // range 0..1000000; the short lists the design's limits, kHdl*)
    const uint64_t s = out_.seed;
    auto pick = [s](std::initializer_list<uint64_t> v) {
        return *(v.begin() + static_cast<std::ptrdiff_t>(s % v.size()));
    };
    const uint32_t wide = static_cast<uint32_t>(pick({0x55555, 0xAAAAA}));
    isa::CostTable& c = cfg.costs;
    for (uint32_t* f :
         {&c.alu, &c.mem, &c.indirect_extra, &c.ring_hop, &c.mask, &c.status, &c.cp,
          &c.branch_taken, &c.video_line, &c.xfer_setup, &c.ext_beat, &c.minmax_extra})
        *f = wide;
    c.shift_bits = static_cast<uint32_t>(pick({5, 2, 7}));
    c.ext_bytes_per_cycle = static_cast<uint32_t>(
        std::min<uint64_t>(pick({5, 2, 8}), static_cast<uint64_t>(detail::kHdlXrows)));
    cfg.pe_regs = static_cast<int>(pick({13, 10, 16}));
    cfg.mask_depth = static_cast<int>(pick({5, 3, 8}));
    cfg.call_depth = static_cast<int>(pick({5, 10, 16}));
    cfg.watchdog_cycles = pick({0x1555555555555555ull, 0x2AAAAAAAAAAAAAAAull});
    NR_ = cfg.pe_regs;
    out_.ending = "halt";
    const uint32_t lo = static_cast<uint32_t>(NR_ - 2);
    // one instruction of every cost class (then a call, below)
    emit(enc(PHASE, 0, 0, 0, static_cast<uint32_t>(pick({0x55, 0xAA, 0xFF}))));
    emit(enc(CLI, 1, 0, 0, cval()));           // cp
    emit(enc(ADD, 1, 2, 3));                   // alu
    emit(enc(0x47, 4, 1, 2));                  // min: minmax
    emit(enc(SHLI, 5, 1, 0, 3));               // shift
    emit(enc(ST, 1, 0, 128, 5));               // mem
    emit(enc(LD, 6, 0, 128, 5));               // mem
    emit(enc(PIDX, lo));                       // (alu)
    emit(enc(LDX, 7, lo, 0, (1u << 29) | 9));  // mem + indirect_extra
    emit(enc(RXL, 2, 1, 0, 1));                // one ring hop
    emit(enc(CEQI, 0, 1, 0, imm8()));          // (alu)
    emit(enc(MIF));                            // mask
    emit(enc(ADD, 3, 3, 3));
    emit(enc(MELSE));
    emit(enc(MEND));
    emit(enc(RANY, kStat));  // status
    const size_t jmp = here();
    emit(enc(JMP));  // cp + branch_taken
    emit(enc(NOP));  // (jumped over)
    patch(jmp, static_cast<uint32_t>(here()));
    set_base(0, 1);  // video line 1, from x = 0
    set_base(1, 0);
    emit(enc(VIN, 0, 0 | 1 << 4, 128, 16));  // video_line
    if (o_.ext_bytes > 0) {
        set_base(kBase0, 20);  // local row 20, external byte 0, 2 bytes
        set_base(kBase0 + 1, 0);
        set_base(kBase0 + 2, 2);
        emit(enc(XLD, kBase0 + 2, kBase0 + 1, kBase0, 0));  // xfer_setup + beats
    }
    // the subroutine at the end of a program whose length flips every bit
    // of the instruction memory's address (65536 words, kHdlImemWords): the
    // call and return move the PC across it
    const size_t call = here();
    emit(enc(CALL));
    emit(enc(HALT));
    const size_t words = static_cast<size_t>(
        std::min<uint64_t>(pick({0x5555, 0xAAAA, 0x10000}), detail::kHdlImemWords));
    while (here() + 2 < words) emit(enc(NOP));
    patch(call, static_cast<uint32_t>(here()));
    emit(enc(ADD, 8, 1, 4));
    emit(enc(RET));
    out_.prog.code = code_;
    out_.prog.phases.clear();
    for (int i = 0; i < 256; ++i) out_.prog.phases.push_back("p" + std::to_string(i));
}

void Gen::run() {
    isa::MachineConfig& cfg = out_.cfg;
    cfg.pes = o_.pes;
    cfg.mem_bytes = o_.mem_bytes;
    cfg.ext_bytes = o_.ext_bytes;
    // images for the video port
    auto img = [&](isa::ImageVideoPort::Image& im, int w, int h) {
        im.width = w;
        im.height = h;
        im.pixels.resize(static_cast<size_t>(w) * static_cast<size_t>(h));
        for (uint8_t& p : im.pixels) p = static_cast<uint8_t>(rng_());
    };
    if (o_.strap_sweep) {
        img(out_.left, o_.pes, 4);
        img(out_.right, o_.pes, 4);
        out_.out_w = o_.pes;
        out_.out_h = 4;
        strap_sweep();
        return;
    }
    if (o_.vary_costs && chance(75)) {
        isa::CostTable& c = cfg.costs;
        c.alu = 1 + static_cast<uint32_t>(u(3));
        c.mem = 1 + static_cast<uint32_t>(u(3));
        c.indirect_extra = static_cast<uint32_t>(u(3));
        c.ring_hop = 1 + static_cast<uint32_t>(u(3));
        c.mask = 1 + static_cast<uint32_t>(u(2));
        c.status = 1 + static_cast<uint32_t>(u(3));
        c.cp = 1 + static_cast<uint32_t>(u(2));
        c.branch_taken = static_cast<uint32_t>(u(4));
        c.video_line = 1 + static_cast<uint32_t>(u(3));
        c.xfer_setup = static_cast<uint32_t>(u(11));
        static const uint32_t bpc[] = {1, 2, 3, 4, 5, 7, 8, 13, 16, 32};
        c.ext_bytes_per_cycle =
            std::min<uint32_t>(bpc[u(10)], static_cast<uint32_t>(detail::kHdlXrows));
        c.shift_bits = 1 + static_cast<uint32_t>(u(7));
        c.minmax_extra = static_cast<uint32_t>(u(3));
        // Board timing (a generator of its own, so that the programs of a
        // seed stay those of earlier versions): a path slower than a byte
        // per cycle, and a camera whose lines arrive while the program runs.
        auto b = [&](uint64_t n) { return board_rng_() % n; };
        if (b(3) == 0) c.ext_beat = 1 + static_cast<uint32_t>(b(4));
        if (b(4) == 0) {
            static const double pix[] = {2.5, 5, 10, 40};
            cfg.board.camera_pixel_mhz = pix[b(4)];
            cfg.board.camera_hblank_px = static_cast<double>(b(17));
        }
    }
    if (chance(20)) cfg.pe_regs = 8;
    NR_ = cfg.pe_regs;
    const int W = o_.pes + static_cast<int>(u(static_cast<uint64_t>(o_.pes))), H = 4;
    img(out_.left, W, H);
    img(out_.right, W, H);
    out_.out_w = W;
    out_.out_h = H;
    for (int i = 0; i < 8; ++i)
        if (chance(50))
            out_.params.emplace_back(static_cast<int>(u(256)), static_cast<uint32_t>(rng_()));
    // prologue: random CP and PE values
    for (int c = 0; c < 8; ++c) emit(enc(CLI, static_cast<uint32_t>(c), 0, 0, cval()));
    for (int r = 0; r < NR_; ++r)
        emit(chance(50) ? enc(PIDX, static_cast<uint32_t>(r), 0, 0, 0)
                        : enc(ADDI, static_cast<uint32_t>(r), static_cast<uint32_t>(r ? r - 1 : 0),
                              0, imm8()));
    for (int i = 0; i < o_.blocks; ++i) block(0);
    const bool fault = chance(o_.fault_percent);
    if (fault)
        fault_ending();
    else
        out_.ending = "halt";
    emit(enc(HALT));
    // subroutines (each may call the next one, up to depth 2)
    std::vector<uint32_t> entry;
    for (int s = 0; s < subs_; ++s) {
        entry.push_back(static_cast<uint32_t>(here()));
        calls_ = 1;
        alu_run(1 + static_cast<int>(u(3)));
        if (chance(30)) block(2);
        emit(enc(RET));
    }
    calls_ = 0;
    for (const auto& [at, s] : call_fix_) patch(at, entry[static_cast<size_t>(s)]);
    out_.prog.code = code_;
    out_.prog.phases = {"default", "p1", "p2", "p3"};
}

}  // namespace randgen

RandomProgram generate_program(uint64_t seed, const GenOptions& opt) {
    RandomProgram p;
    p.seed = seed;
    randgen::Gen g(seed, opt, p);
    g.run();
    return p;
}

}  // namespace imap::rtl
