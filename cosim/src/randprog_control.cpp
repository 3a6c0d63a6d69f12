// The generator's blocks and control flow: the choice of a block
// (Gen::block: a run of PE operations, a mask block, a loop, a branch, a
// memory, ring, transfer, status or video block, CP instructions), the mask
// stack's mif / melse / mend nesting (Gen::mask_block, up to max_mask_), CP
// loops (Gen::loop_block, up to four deep), branches and calls
// (Gen::branch_block), status reductions branched on (Gen::status_block)
// and the CP's own instructions (Gen::cp_block).
#include "randprog_gen.hpp"

namespace imap::rtl::randgen {

void Gen::status_block() {
    emit(enc(static_cast<uint8_t>(CEQ + u(6)), 0, static_cast<uint32_t>(reg()),
             static_cast<uint32_t>(reg())));
    emit(enc(chance(50) ? RANY : RALL, kStat));
    // branch on the result over one instruction
    const size_t at = here();
    emit(enc(chance(50) ? BNZ : BZ, 0, kStat, 0, 0));
    pe_op();
    patch(at, static_cast<uint32_t>(here()));
}

void Gen::cp_block() {
    const int d = creg(), a = creg(), b = creg();
    switch (u(8)) {
        case 0:
            emit(enc(CLI, static_cast<uint32_t>(d), 0, 0, cval()));
            break;
        case 1:
            emit(enc(CMOV, static_cast<uint32_t>(d), static_cast<uint32_t>(a)));
            break;
        case 2: {
            static const uint8_t ops[] = {CADD, CSUB, CAND, COR, CXOR};
            emit(enc(ops[u(5)], static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                     static_cast<uint32_t>(b)));
            break;
        }
        case 3: {
            static const uint8_t ops[] = {CADDI, CSUBI, CANDI, CORI, CXORI};
            emit(enc(ops[u(5)], static_cast<uint32_t>(d), static_cast<uint32_t>(a), 0, cval()));
            break;
        }
        case 4: {
            static const uint8_t ops[] = {CSHLI, CSHRI, CSRAI};
            emit(enc(ops[u(3)], static_cast<uint32_t>(d), static_cast<uint32_t>(a), 0,
                     static_cast<uint32_t>(u(32))));
            break;
        }
        case 5: {
            const uint32_t at = static_cast<uint32_t>(u(256));
            if (chance(50)) {
                emit(enc(CST, static_cast<uint32_t>(d), 0, 128, at));
            } else {
                set_base(kBase0, at / 2);
                emit(enc(CLD, static_cast<uint32_t>(d), 0, kBase0, at - at / 2));
            }
            break;
        }
        case 6:
            emit(enc(PHASE, 0, 0, 0, static_cast<uint32_t>(u(4))));
            break;
        default:
            emit(enc(NOP));
            break;
    }
}

void Gen::mask_block(int level) {
    if (depth_ >= max_mask_) {
        alu_run(1);
        return;
    }
    if (chance(70))
        emit(enc(static_cast<uint8_t>(CEQ + u(6)), 0, static_cast<uint32_t>(reg()),
                 static_cast<uint32_t>(reg())));
    else
        emit(enc(static_cast<uint8_t>(CEQI + u(6)), 0, static_cast<uint32_t>(reg()), 0, imm8()));
    emit(enc(MIF));
    ++depth_;
    alu_run(1 + static_cast<int>(u(3)));
    if (chance(40)) block(level + 1);
    if (chance(60)) {
        emit(enc(MELSE));
        alu_run(1 + static_cast<int>(u(3)));
        if (chance(25)) mask_block(level + 1);
    }
    emit(enc(MEND));
    --depth_;
}

void Gen::loop_block(int level) {
    if (loops_ >= 4) {
        alu_run(1);
        return;
    }
    const int c = kLoop0 + loops_;
    ++loops_;
    emit(enc(CLI, static_cast<uint32_t>(c), 0, 0, 1 + static_cast<uint32_t>(u(3))));
    const uint32_t top = static_cast<uint32_t>(here());
    alu_run(1 + static_cast<int>(u(3)));
    if (chance(50)) block(level + 1);
    emit(enc(LOOP, 0, static_cast<uint32_t>(c), 0, top));
    --loops_;
}

void Gen::branch_block(int level) {
    const size_t at = here();
    switch (u(8)) {
        case 0:
            emit(enc(JMP));
            break;
        case 1:
            emit(enc(BEQ, 0, static_cast<uint32_t>(creg()), static_cast<uint32_t>(creg())));
            break;
        case 2:
            emit(enc(BNE, 0, static_cast<uint32_t>(creg()), static_cast<uint32_t>(creg())));
            break;
        case 3:
            emit(enc(BLT, 0, static_cast<uint32_t>(creg()), static_cast<uint32_t>(creg())));
            break;
        case 4:
            emit(enc(BGE, 0, static_cast<uint32_t>(creg()), static_cast<uint32_t>(creg())));
            break;
        case 5:
            emit(enc(BZ, 0, static_cast<uint32_t>(creg())));
            break;
        case 6:
            emit(enc(BNZ, 0, static_cast<uint32_t>(creg())));
            break;
        default: {  // a call to a subroutine generated after the halt
            if (calls_ < 2) {
                emit(enc(CALL));
                call_fix_.emplace_back(at, subs_++);
            } else {
                emit(enc(NOP));
            }
            return;
        }
    }
    if (chance(10)) {  // a taken branch to the next instruction
        patch(at, static_cast<uint32_t>(here()));
        return;
    }
    alu_run(1 + static_cast<int>(u(2)));
    if (chance(30)) block(level + 1);
    patch(at, static_cast<uint32_t>(here()));
}

void Gen::block(int level) {
    if (level > 3) {
        alu_run(1);
        return;
    }
    switch (u(16)) {
        case 0:
        case 1:
        case 2:
            alu_run(1 + static_cast<int>(u(5)));
            break;
        case 3:
        case 4:
            mask_block(level);
            break;
        case 5:
            loop_block(level);
            break;
        case 6:
        case 7:
            branch_block(level);
            break;
        case 8:
            mem_block();
            break;
        case 9:
            memx_block();
            break;
        case 10:
            ring_block();
            break;
        case 11:
            xfer_block();
            break;
        case 12:
            status_block();
            break;
        case 13:
            video_block();
            break;
        case 14:
            if (depth_ == 0 && chance(30))
                emit(enc(MALL));
            else
                cp_block();
            break;
        default:
            cp_block();
            break;
    }
}

}  // namespace imap::rtl::randgen
