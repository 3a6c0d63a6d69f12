// The generator's memory and I/O instructions: local memory loads and
// stores, absolute and based (Gen::mem_block), per-PE indirect addressing in
// range of GenOptions::mem_bytes (Gen::memx_block), external transfers of
// drawn lengths, some under a narrower mask (Gen::xfer_block, GenOptions::
// ext_bytes), and video port lines in and out of the program's images
// (Gen::video_block).
#include <algorithm>

#include "randprog_gen.hpp"

namespace imap::rtl::randgen {

void Gen::mem_block() {
    const uint32_t mem = o_.mem_bytes;
    const int c = kBase0 + static_cast<int>(u(3));
    const uint32_t base = static_cast<uint32_t>(u(mem));
    if (chance(30)) {  // absolute address
        emit(enc(chance(50) ? LD : ST, static_cast<uint32_t>(reg()), 0, 128,
                 static_cast<uint32_t>(u(mem))));
        return;
    }
    set_base(c, base);
    if (chance(40))
        emit(enc(CADDI, static_cast<uint32_t>(c), static_cast<uint32_t>(c), 0,
                 0));  // forwarded twice
    const int32_t off = static_cast<int32_t>(u(mem)) - static_cast<int32_t>(base);
    emit(enc(chance(50) ? ST : LD, static_cast<uint32_t>(reg()), 0, static_cast<uint32_t>(c),
             static_cast<uint32_t>(off)));
    if (chance(50))
        emit(enc(LD, static_cast<uint32_t>(reg()), 0, static_cast<uint32_t>(c),
                 static_cast<uint32_t>(off)));
}

void Gen::memx_block() {
    // per-PE address lo (masked to 6 bits) [+ hi * 256] [+ cN] + off, in range
    const int lo = NR_ - 2, hi = NR_ - 1;
    const uint32_t mem = o_.mem_bytes;
    // the PE index (pidx: ra is an unused field, must be 0) or a register's
    // value; the draws are sequenced, not function arguments (whose order
    // of evaluation the compiler chooses)
    if (chance(50)) {
        emit(enc(PIDX, static_cast<uint32_t>(lo), 0, 0, 0));
    } else {
        const uint32_t src = chance(50) ? 0u : static_cast<uint32_t>(reg());
        emit(enc(MOV, static_cast<uint32_t>(lo), src, 0, 0));
    }
    emit(enc(0x54, static_cast<uint32_t>(lo), static_cast<uint32_t>(lo), 0, 0x3f));  // andi
    const bool use_hi = mem >= 512 && chance(40);
    uint32_t imm = 0;
    int64_t room = static_cast<int64_t>(mem) - 64;
    if (use_hi) {
        const uint32_t h = static_cast<uint32_t>(u(std::max<uint32_t>(mem / 256 - 1, 1)));
        emit(enc(LI, static_cast<uint32_t>(hi), 0, 0, h));
        room -= 256 * h;
    } else {
        imm |= 1u << 29;
    }
    int64_t used = 0;
    if (chance(40) && room > 0) {
        const int c = kBase0 + static_cast<int>(u(3));
        const uint32_t v = static_cast<uint32_t>(u(static_cast<uint64_t>(room)));
        set_base(c, v);
        used = v;
        imm |= 1u << 28 | static_cast<uint32_t>(c) << 24;
    }
    const int64_t left = room - used;
    const int32_t off = left > 0 ? static_cast<int32_t>(u(static_cast<uint64_t>(left))) : 0;
    imm |= static_cast<uint32_t>(off) & 0xffffffu;
    emit(enc(chance(50) ? LDX : STX, static_cast<uint32_t>(reg()), static_cast<uint32_t>(lo),
             use_hi ? static_cast<uint32_t>(hi) : 0u, imm));
}

void Gen::xfer_block() {
    if (o_.ext_bytes == 0) return;
    const int P = o_.pes;
    uint32_t len;
    switch (u(6)) {
        case 0:
            len = 0;
            break;
        case 1:
            len = 1;
            break;
        case 2:
            len = 2 + static_cast<uint32_t>(u(6));
            break;
        case 3:
            len = static_cast<uint32_t>(P);
            break;
        default:
            len = static_cast<uint32_t>(u(40));
            break;
    }
    len = std::min(len, o_.mem_bytes);
    const uint32_t lb = static_cast<uint32_t>(u(o_.mem_bytes - len + 1));
    const uint32_t eb = static_cast<uint32_t>(u(std::min<uint32_t>(o_.ext_bytes, 4096) - len + 1));
    set_base(kBase0, lb);
    set_base(kBase0 + 1, eb);
    set_base(kBase0 + 2, len);
    const bool xst = chance(50);
    const uint32_t base_reg = chance(20) ? 128u : kBase0;
    const uint32_t off = chance(20) ? lb : 0u;
    // the transferred rows are mostly never-written zeros over zeros: a
    // register stored into the last local row of the range (the xst's
    // source, the xld's destination) makes a dropped or misplaced last row
    // visible
    const uint64_t last = uint64_t{base_reg == 128u ? 0u : lb} + off + len - 1;
    // a transfer under a narrower mask (its own mif .. mend): the row stored
    // before it differs from the other memory's in the PEs it masks, so a
    // masked PE whose bytes move, or a cost counting them, shows
    const bool narrow = depth_ < max_mask_ && chance(40);
    if (len > 0 && last < o_.mem_bytes && (narrow || chance(60)))
        emit(enc(ST, static_cast<uint32_t>(reg()), 0, base_reg, off + len - 1));
    if (narrow) {
        emit(enc(static_cast<uint8_t>(CEQI + u(6)), 0, static_cast<uint32_t>(reg()), 0, imm8()));
        emit(enc(MIF));
        ++depth_;
    }
    emit(enc(xst ? XST : XLD, kBase0 + 2, kBase0 + 1, base_reg, off));
    if (narrow) {
        emit(enc(MEND));
        --depth_;
    }
    if (chance(30)) emit(enc(LD, static_cast<uint32_t>(reg()), 0, 128, lb));
}

void Gen::video_block() {
    const int y = static_cast<int>(u(static_cast<uint64_t>(out_.left.height)));
    const int x = chance(30) ? static_cast<int>(u(static_cast<uint64_t>(out_.left.width + 4))) : 0;
    const int cy = creg(), cx = (cy + 1 + static_cast<int>(u(7))) % 8;
    set_base(cy, static_cast<uint32_t>(y));
    set_base(cx, static_cast<uint32_t>(x));
    const uint32_t row = static_cast<uint32_t>(u(o_.mem_bytes));
    emit(enc(chance(50) ? VIN : VOUT, static_cast<uint32_t>(u(2)),
             static_cast<uint32_t>(cy | cx << 4), 128, row));
}

}  // namespace imap::rtl::randgen
