// The generator's PE data-path instructions (docs/isa.md section 3): one
// random PE operation (Gen::pe_op) of the ALU (register and immediate
// forms, min / max, carry chains), moves and selects, the shifter, the
// comparator, a ring transfer or a local memory access; and the ring
// transfers' distances and directions (Gen::ring_block), drawn around the
// array size P (GenOptions::pes).
#include <algorithm>

#include "randprog_gen.hpp"

namespace imap::rtl::randgen {

void Gen::pe_op() {
    const int d = reg(), a = reg(), b = reg();
    switch (u(12)) {
        case 0:
        case 1: {  // Rrr ALU / min / max
            static const uint8_t ops[] = {0x40, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47, 0x48};
            const int bb = chance(15) ? a : b;  // same-register operands
            emit(enc(ops[u(9)], static_cast<uint32_t>(chance(15) ? a : d), static_cast<uint32_t>(a),
                     static_cast<uint32_t>(bb)));
            break;
        }
        case 2:
        case 3: {  // Rri8
            static const uint8_t ops[] = {0x50, 0x51, 0x52, 0x53, 0x54, 0x55, 0x56, 0x57, 0x58};
            emit(enc(ops[u(9)], static_cast<uint32_t>(d), static_cast<uint32_t>(a), 0, imm8()));
            break;
        }
        case 4: {  // moves and selects
            switch (u(9)) {
                case 0:
                    emit(enc(MOV, static_cast<uint32_t>(d), static_cast<uint32_t>(a)));
                    break;
                case 1:
                    emit(enc(LI, static_cast<uint32_t>(d), 0, 0, imm8()));
                    break;
                case 2:
                    emit(enc(LC, static_cast<uint32_t>(d), static_cast<uint32_t>(creg())));
                    break;
                case 3:
                    emit(enc(LCB, static_cast<uint32_t>(d), static_cast<uint32_t>(creg()), 0,
                             static_cast<uint32_t>(u(4))));
                    break;
                case 4:
                    emit(enc(PIDX, static_cast<uint32_t>(d), 0, 0, static_cast<uint32_t>(u(4))));
                    break;
                case 5:
                    emit(enc(SETC, static_cast<uint32_t>(d)));
                    break;
                case 6:
                    emit(enc(SETT, static_cast<uint32_t>(d)));
                    break;
                case 7:
                    emit(enc(CSEL, static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                             static_cast<uint32_t>(b)));
                    break;
                default:
                    emit(enc(TSEL, static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                             static_cast<uint32_t>(b)));
                    break;
            }
            break;
        }
        case 5:
        case 6: {  // shifter
            switch (u(6)) {
                case 0:
                    emit(enc(SHLI, static_cast<uint32_t>(d), static_cast<uint32_t>(a), 0,
                             static_cast<uint32_t>(u(8))));
                    break;
                case 1:
                    emit(enc(SHRI, static_cast<uint32_t>(d), static_cast<uint32_t>(a), 0,
                             static_cast<uint32_t>(u(8))));
                    break;
                case 2:
                    emit(enc(ROLC, static_cast<uint32_t>(d), static_cast<uint32_t>(a)));
                    break;
                case 3:
                    emit(enc(RORC, static_cast<uint32_t>(d), static_cast<uint32_t>(a)));
                    break;
                case 4:
                    emit(enc(SHLV, static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                             static_cast<uint32_t>(b)));
                    break;
                default:
                    emit(enc(SHRV, static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                             static_cast<uint32_t>(b)));
                    break;
            }
            break;
        }
        case 7:
        case 8: {  // comparator
            const uint64_t k = u(14);
            if (k < 6)
                emit(enc(static_cast<uint8_t>(CEQ + k), 0, static_cast<uint32_t>(a),
                         static_cast<uint32_t>(b)));
            else if (k < 12)
                emit(enc(static_cast<uint8_t>(CEQI + (k - 6)), 0, static_cast<uint32_t>(a), 0,
                         imm8()));
            else
                emit(enc(k == 12 ? TC : TNOT));
            break;
        }
        case 9:
            ring_block();
            break;
        case 10:
            mem_block();
            break;
        default: {  // a carry chain
            emit(enc(ADD, static_cast<uint32_t>(d), static_cast<uint32_t>(a),
                     static_cast<uint32_t>(b)));
            emit(enc(static_cast<uint8_t>(0x41 + 2 * u(2)), static_cast<uint32_t>(reg()),
                     static_cast<uint32_t>(reg()), static_cast<uint32_t>(reg())));
            break;
        }
    }
}

void Gen::ring_block() {
    const int P = o_.pes;
    uint32_t k;
    switch (u(7)) {
        case 0:
            k = 1;
            break;
        case 1:
            k = static_cast<uint32_t>(P - 1);
            break;
        case 2:
            k = static_cast<uint32_t>(P);
            break;
        case 3:
            k = static_cast<uint32_t>(P + 1);
            break;
        case 4:
            k = static_cast<uint32_t>(2 * P + u(static_cast<uint64_t>(P)));
            break;
        case 5:
            k = chance(3) ? 65535u : static_cast<uint32_t>(3 * P + u(100));
            break;
        default:
            k = 2 + static_cast<uint32_t>(u(static_cast<uint64_t>(std::max(P - 2, 1))));
            break;
    }
    emit(enc(chance(50) ? RXL : RXR, static_cast<uint32_t>(reg()), static_cast<uint32_t>(reg()), 0,
             k));
}

}  // namespace imap::rtl::randgen
