// The instruction handlers of the executor, compiled once per SIMD path.
//
// Every handler is Exec::exec<Op, Full>: a single loop over the lanes (64
// lanes per step, rows padded to a multiple of 64) with the mask applied by
// blending (dst = M ? result : dst); Full = true is the same instruction for
// a machine whose PEs are all active, without the blend. The per-lane
// semantics come from semantics.hpp. The bodies are always_inline and are
// instantiated inside three wrappers that differ only in their GCC `target`
// attribute (baseline, AVX2, AVX-512), so the vectoriser emits each path
// from the same source; functions the bodies call without inlining them are
// compiled for the baseline, so no wider instruction escapes a path the CPU
// cannot run. Machine::set_simd_path picks the table.
#include <cstring>
#include <exception>
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "exec.hpp"
#include "imap/isa/encoding.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/semantics.hpp"

namespace imap::isa {

namespace {

using detail::kChunk;
using detail::kFixedLanes;
using detail::kFlagNoHigh;

#define IMAP_INLINE [[gnu::always_inline]] inline

// k is 0x00 or 0xFF: x where k is set, old elsewhere.
IMAP_INLINE uint8_t blend(uint8_t k, uint8_t x, uint8_t old) {
    return static_cast<uint8_t>((x & k) | (old & static_cast<uint8_t>(~k)));
}
IMAP_INLINE uint8_t lane_mask(uint8_t m) {
    return static_cast<uint8_t>(-m);
}

// Every lane loop reads and writes only element p of its rows, and two rows
// are either the same row (rd == ra) or disjoint, so no iteration depends on
// another: `ivdep` says exactly that and spares the run-time alias checks.
#if defined(__GNUC__) && !defined(__clang__)
#define IMAP_IVDEP _Pragma("GCC ivdep")
#else
#define IMAP_IVDEP
#endif

// for p in [0, n), n a multiple of kChunk, in steps of kChunk lanes (the
// inner loop has a constant trip count: one to four vectors, no remainder).
#define IMAP_LANES(n, p, ...)                               \
    for (size_t q_ = 0; q_ < (n); q_ += kChunk) {           \
        IMAP_IVDEP for (size_t j_ = 0; j_ < kChunk; ++j_) { \
            const size_t p = q_ + j_;                       \
            __VA_ARGS__                                     \
        }                                                   \
    }

// reg[p] = M ? mem[idx[p]] : reg[p] for p < S (S a multiple of 64): the
// gather of ldx. idx[p] + 3 stays inside the memory block (its slack), so
// the vector paths may load a 32-bit word at every index.
template <SimdPath Path, bool Full>
void gather_rows(uint8_t* reg, const uint8_t* mem, const uint32_t* idx, const uint8_t* mk,
                 size_t S);

template <>
inline void gather_rows<SimdPath::Generic, false>(uint8_t* reg, const uint8_t* mem,
                                                  const uint32_t* idx, const uint8_t* mk,
                                                  size_t S) {
    for (size_t p = 0; p < S; ++p) reg[p] = blend(lane_mask(mk[p]), mem[idx[p]], reg[p]);
}
template <>
inline void gather_rows<SimdPath::Generic, true>(uint8_t* reg, const uint8_t* mem,
                                                 const uint32_t* idx, const uint8_t*, size_t S) {
    for (size_t p = 0; p < S; ++p) reg[p] = mem[idx[p]];
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define IMAP_HAVE_X86_PATHS 1
#define IMAP_TARGET_AVX2 __attribute__((target("avx2")))
#define IMAP_TARGET_AVX512 \
    __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,prefer-vector-width=512")))

template <bool Full>
IMAP_TARGET_AVX2 void gather_avx2(uint8_t* reg, const uint8_t* mem, const uint32_t* idx,
                                  const uint8_t* mk, size_t S) {
    // low byte of each 32-bit word to the low 4 bytes of each 128-bit half
    const __m256i pick =
        _mm256_setr_epi8(0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 0, 4, 8, 12,
                         -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1);
    const __m256i join = _mm256_setr_epi32(0, 4, 1, 1, 1, 1, 1, 1);
    for (size_t p = 0; p < S; p += 8) {
        const __m256i vi = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx + p));
        const __m256i v = _mm256_i32gather_epi32(reinterpret_cast<const int*>(mem), vi, 1);
        const __m256i b = _mm256_permutevar8x32_epi32(_mm256_shuffle_epi8(v, pick), join);
        const __m128i x = _mm256_castsi256_si128(b);  // 8 bytes
        if constexpr (Full) {
            _mm_storel_epi64(reinterpret_cast<__m128i*>(reg + p), x);
        } else {
            const __m128i old = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(reg + p));
            const __m128i k = _mm_cmpgt_epi8(
                _mm_loadl_epi64(reinterpret_cast<const __m128i*>(mk + p)), _mm_setzero_si128());
            _mm_storel_epi64(reinterpret_cast<__m128i*>(reg + p), _mm_blendv_epi8(old, x, k));
        }
    }
}

template <bool Full>
IMAP_TARGET_AVX512 void gather_avx512(uint8_t* reg, const uint8_t* mem, const uint32_t* idx,
                                      const uint8_t* mk, size_t S) {
    for (size_t p = 0; p < S; p += 16) {
        const __m512i vi = _mm512_loadu_si512(idx + p);
        // (the masked forms with explicit zeros: GCC 12's plain forms start
        // from an "undefined" value that -Wmaybe-uninitialized reports)
        const __m512i v = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), 0xFFFF, vi, mem, 1);
        const __m128i b = _mm512_maskz_cvtepi32_epi8(0xFFFF, v);  // low byte of each word
        if constexpr (Full) {
            _mm_storeu_si128(reinterpret_cast<__m128i*>(reg + p), b);
        } else {
            const __m128i m = _mm_loadu_si128(reinterpret_cast<const __m128i*>(mk + p));
            _mm_mask_storeu_epi8(reg + p, _mm_test_epi8_mask(m, m), b);
        }
    }
}

template <>
inline void gather_rows<SimdPath::Avx2, false>(uint8_t* reg, const uint8_t* mem,
                                               const uint32_t* idx, const uint8_t* mk, size_t S) {
    gather_avx2<false>(reg, mem, idx, mk, S);
}
template <>
inline void gather_rows<SimdPath::Avx2, true>(uint8_t* reg, const uint8_t* mem, const uint32_t* idx,
                                              const uint8_t* mk, size_t S) {
    gather_avx2<true>(reg, mem, idx, mk, S);
}
template <>
inline void gather_rows<SimdPath::Avx512, false>(uint8_t* reg, const uint8_t* mem,
                                                 const uint32_t* idx, const uint8_t* mk, size_t S) {
    gather_avx512<false>(reg, mem, idx, mk, S);
}
template <>
inline void gather_rows<SimdPath::Avx512, true>(uint8_t* reg, const uint8_t* mem,
                                                const uint32_t* idx, const uint8_t* mk, size_t S) {
    gather_avx512<true>(reg, mem, idx, mk, S);
}
#else
template <>
inline void gather_rows<SimdPath::Avx2, false>(uint8_t* reg, const uint8_t* mem,
                                               const uint32_t* idx, const uint8_t* mk, size_t S) {
    gather_rows<SimdPath::Generic, false>(reg, mem, idx, mk, S);
}
template <>
inline void gather_rows<SimdPath::Avx2, true>(uint8_t* reg, const uint8_t* mem, const uint32_t* idx,
                                              const uint8_t* mk, size_t S) {
    gather_rows<SimdPath::Generic, true>(reg, mem, idx, mk, S);
}
template <>
inline void gather_rows<SimdPath::Avx512, false>(uint8_t* reg, const uint8_t* mem,
                                                 const uint32_t* idx, const uint8_t* mk, size_t S) {
    gather_rows<SimdPath::Generic, false>(reg, mem, idx, mk, S);
}
template <>
inline void gather_rows<SimdPath::Avx512, true>(uint8_t* reg, const uint8_t* mem,
                                                const uint32_t* idx, const uint8_t* mk, size_t S) {
    gather_rows<SimdPath::Generic, true>(reg, mem, idx, mk, S);
}
#endif

}  // namespace

// ---------------------------------------------------------------------------
// Instruction semantics.
struct Exec {
    static int64_t cpv(const Machine& m, uint32_t r) { return as_signed(m.creg_[r]); }

    // ---- cold paths: messages (compiled once, never inlined) ----
    [[noreturn, gnu::cold, gnu::noinline]] static void mem_range_fault(const Machine& m,
                                                                       const char* mn, int64_t a) {
        m.fault(std::string(mn) + ": address " + std::to_string(a) +
                    " out of range (local memory is " + std::to_string(m.cfg_.mem_bytes) +
                    " bytes per PE: 0.." + std::to_string(m.cfg_.mem_bytes - 1) + ", all PEs)",
                Fault::kNone, a);
    }
    [[noreturn, gnu::cold, gnu::noinline]] static void ldx_fault(const Machine& m, bool store,
                                                                 const uint8_t* lo,
                                                                 const uint8_t* hi, int64_t base) {
        // The first active PE whose address is out of range, as a per-PE loop finds it.
        const size_t P = static_cast<size_t>(m.P_);
        const int64_t size = m.cfg_.mem_bytes;
        for (size_t p = 0; p < P; ++p) {
            if (!m.m_[p]) continue;
            const int64_t a = base + ((int64_t{hi[p]} << 8) | int64_t{lo[p]});
            if (a < 0 || a >= size)
                m.fault(std::string(store ? "stx" : "ldx") + ": PE " + std::to_string(p) +
                            " address " + std::to_string(a) + " out of range (local memory is " +
                            std::to_string(size) + " bytes per PE: 0.." + std::to_string(size - 1) +
                            ")",
                        static_cast<int64_t>(p), a);
        }
        m.fault(std::string(store ? "stx" : "ldx") + ": address check failed");
    }
    [[noreturn, gnu::cold, gnu::noinline]] static void plain_fault(const Machine& m,
                                                                   const std::string& msg) {
        m.fault(msg);
    }

    static int64_t mem_addr(const Machine& m, const Decoded& d, const char* mn) {
        const int64_t a = cpv(m, d.b) + d.imm;
        if (a < 0 || a >= static_cast<int64_t>(m.cfg_.mem_bytes)) mem_range_fault(m, mn, a);
        return a;
    }

    // ---- lane loop shapes ----

    // dst = M ? src : dst over all lanes.
    template <bool Full>
    IMAP_INLINE static void write_masked(Machine& m, uint32_t dst_off, const uint8_t* src) {
        const size_t S = m.S_;
        uint8_t* dst = m.lanes_ + dst_off;
        const uint8_t* mk = m.m_;
        IMAP_LANES(S, p, dst[p] = Full ? src[p] : blend(lane_mask(mk[p]), src[p], dst[p]);)
    }
    template <bool Full>
    IMAP_INLINE static void write_masked_value(Machine& m, uint32_t dst_off, uint8_t v) {
        const size_t S = m.S_;
        uint8_t* dst = m.lanes_ + dst_off;
        const uint8_t* mk = m.m_;
        IMAP_LANES(S, p, dst[p] = Full ? v : blend(lane_mask(mk[p]), v, dst[p]);)
    }

    // rd = ra op rb (N < 0), or ra op N (N >= 0: an immediate folded into the
    // code, so the staged shift of semantics.hpp becomes a single shift), or
    // ra op imm (Imm).
    template <Op O, bool Full, bool Imm, int N = -1>
    IMAP_INLINE static void alu(Machine& m, const Decoded& d) {
        const size_t S = m.S_;
        uint8_t* L = m.lanes_;
        uint8_t* dst = L + d.d;
        const uint8_t* a = L + d.a;
        const uint8_t* b = L + d.b;
        const uint8_t bi = N >= 0 ? static_cast<uint8_t>(N) : static_cast<uint8_t>(d.imm);
        uint8_t* c = m.c_;
        const uint8_t* mk = m.m_;
        IMAP_LANES(S, p, {
            const sem::LaneOut o = sem::alu<O>(a[p], Imm ? bi : b[p], c[p]);
            if constexpr (Full) {
                dst[p] = o.r;
                if constexpr (sem::writes_carry(O)) c[p] = o.c;
            } else {
                const uint8_t k = lane_mask(mk[p]);
                dst[p] = blend(k, o.r, dst[p]);
                if constexpr (sem::writes_carry(O)) c[p] = blend(k, o.c, c[p]);
            }
        })
    }

    template <Op O, bool Full>
    IMAP_INLINE static void shift_imm(Machine& m, const Decoded& d) {
        switch (d.imm & 7) {
            case 0:
                return alu<O, Full, true, 0>(m, d);
            case 1:
                return alu<O, Full, true, 1>(m, d);
            case 2:
                return alu<O, Full, true, 2>(m, d);
            case 3:
                return alu<O, Full, true, 3>(m, d);
            case 4:
                return alu<O, Full, true, 4>(m, d);
            case 5:
                return alu<O, Full, true, 5>(m, d);
            case 6:
                return alu<O, Full, true, 6>(m, d);
            default:
                return alu<O, Full, true, 7>(m, d);
        }
    }

    template <Op O, bool Full, bool Imm>
    IMAP_INLINE static void cmp(Machine& m, const Decoded& d) {
        const size_t S = m.S_;
        const uint8_t* L = m.lanes_;
        const uint8_t* a = L + d.a;
        const uint8_t* b = L + d.b;
        const uint8_t bi = static_cast<uint8_t>(d.imm);
        uint8_t* t = m.t_;
        const uint8_t* mk = m.m_;
        IMAP_LANES(S, p, {
            const uint8_t v = sem::compare<O>(a[p], Imm ? bi : b[p]);
            t[p] = Full ? v : blend(lane_mask(mk[p]), v, t[p]);
        })
    }

    // rd = sel ? ra : rb, sel = C or T lanes.
    template <bool Full>
    IMAP_INLINE static void select(Machine& m, const Decoded& d, const uint8_t* sel) {
        const size_t S = m.S_;
        uint8_t* L = m.lanes_;
        uint8_t* dst = L + d.d;
        const uint8_t* a = L + d.a;
        const uint8_t* b = L + d.b;
        const uint8_t* mk = m.m_;
        IMAP_LANES(S, p, {
            const uint8_t v = blend(lane_mask(sel[p]), a[p], b[p]);
            dst[p] = Full ? v : blend(lane_mask(mk[p]), v, dst[p]);
        })
    }

    // T = C / T = !T.
    template <bool Full, bool FromCarry>
    IMAP_INLINE static void tflag(Machine& m) {
        const size_t S = m.S_;
        uint8_t* t = m.t_;
        const uint8_t* cf = m.c_;
        const uint8_t* mk = m.m_;
        IMAP_LANES(S, p, {
            const uint8_t v = FromCarry ? cf[p] : static_cast<uint8_t>(t[p] ^ 1u);
            t[p] = Full ? v : blend(lane_mask(mk[p]), v, t[p]);
        })
    }

    // Broadcast address. A row of memory is P bytes; the loops run over the
    // padded S lanes: a load may read up to S - P bytes past the row (the
    // block has slack) into the register's padding lanes, a store writes
    // them only through the mask (padding lanes of M are 0, so those bytes
    // are written back unchanged). The unmasked store needs S == P.
    template <bool Store, bool Full>
    IMAP_INLINE static void ldst(Machine& m, const Decoded& d) {
        const size_t P = static_cast<size_t>(m.P_), S = m.S_;
        const int64_t addr = mem_addr(m, d, Store ? "st" : "ld");
        uint8_t* row = m.mem_ + static_cast<size_t>(addr) * P;
        uint8_t* reg = m.lanes_ + d.d;
        const uint8_t* mk = m.m_;
        if constexpr (Store) {
            if (Full && S == P)
                IMAP_LANES(S, p, row[p] = reg[p];)
            else
                IMAP_LANES(S, p, row[p] = blend(lane_mask(mk[p]), reg[p], row[p]);)
        } else {
            IMAP_LANES(S, p, reg[p] = Full ? row[p] : blend(lane_mask(mk[p]), row[p], reg[p]);)
        }
    }

    // Per-PE address: CP base + imm + (hi << 8 | lo). Only active PEs access
    // memory, and every active address is checked before anything is written.
    // First, in vector code over all lanes: the 16-bit offsets, their range
    // over the active lanes (padding lanes of M are 0), and each lane's cell
    // index (address * P + p; inactive lanes get a dummy cell in the slack
    // after the memory). Then one access per lane: a gather on the vector
    // paths for ldx, a plain loop for stx (every active lane stores into its
    // own column, the inactive ones into the dummy cell).
    template <bool Store, bool Full, SimdPath Path>
    IMAP_INLINE static void ldstx(Machine& m, const Decoded& d) {
        const size_t P = static_cast<size_t>(m.P_), S = m.S_;
        const uint8_t* L = m.lanes_;
        const uint8_t* lo = L + d.a;
        const uint8_t* hi = (d.flags & kFlagNoHigh) ? m.zero_ : L + d.b;
        const int64_t base = cpv(m, d.aux) + d.imm;
        const int64_t size = m.cfg_.mem_bytes;
        const uint8_t* mk = m.m_;
        uint32_t* idx = reinterpret_cast<uint32_t*>(m.scratch_);  // 4 * S bytes
        const uint32_t* lane_no = m.lane_no_;
        // Exact for every address in range: the memory is at most 1 GiB.
        const uint32_t b32 = static_cast<uint32_t>(base), P32 = static_cast<uint32_t>(P);
        const uint32_t dummy = m.cfg_.mem_bytes * P32;
        uint16_t mn = 0xFFFF, mx = 0;
        IMAP_LANES(S, p, {
            const uint16_t o = static_cast<uint16_t>((hi[p] << 8) | lo[p]);
            const uint16_t k = static_cast<uint16_t>(-mk[p]);
            // inactive lanes: min over 0xFFFF, max over 0
            const uint16_t omin = static_cast<uint16_t>(o | static_cast<uint16_t>(~k));
            const uint16_t omax = static_cast<uint16_t>(o & k);
            mn = omin < mn ? omin : mn;
            mx = omax > mx ? omax : mx;
            const uint32_t cell = (b32 + o) * P32 + lane_no[p];
            idx[p] = mk[p] ? cell : dummy;
        })
        const bool any = mn <= mx;
        if (!any) return;
        if (base + mn < 0 || base + mx >= size) ldx_fault(m, Store, lo, hi, base);
        uint8_t* mem = m.mem_;
        uint8_t* reg = m.lanes_ + d.d;
        if constexpr (Store) {
            for (size_t p = 0; p < P; ++p) mem[idx[p]] = reg[p];
        } else {
            gather_rows<Path, Full>(reg, mem, idx, mk, S);
        }
    }

    template <bool Store>
    static void xfer(Machine& m, const Decoded& d) {
        const char* mn = Store ? "xst" : "xld";
        const size_t P = static_cast<size_t>(m.P_);
        if (m.cfg_.ext_bytes == 0)
            plain_fault(m, std::string(mn) + ": external memory disabled (ext_bytes = 0)");
        const int64_t len = cpv(m, d.d);
        const int64_t ext = cpv(m, d.a);
        const int64_t loc = cpv(m, d.b) + d.imm;
        const int64_t msize = m.cfg_.mem_bytes, esize = m.cfg_.ext_bytes;
        if (len < 0)
            plain_fault(m, std::string(mn) + ": negative length " + std::to_string(len) + " (c" +
                               std::to_string(d.d) + ")");
        if (loc < 0 || loc + len > msize)
            m.fault(std::string(mn) + ": local range " + std::to_string(loc) + ".." +
                        std::to_string(loc + len - 1) + " (" + std::to_string(len) +
                        " bytes) out of range (local memory is " + std::to_string(msize) +
                        " bytes per PE)",
                    Fault::kNone, loc < 0 ? loc : loc + len - 1);
        if (ext < 0 || ext + len > esize)
            m.fault(std::string(mn) + ": external range " + std::to_string(ext) + ".." +
                        std::to_string(ext + len - 1) + " (" + std::to_string(len) +
                        " bytes) out of range (external memory is " + std::to_string(esize) +
                        " bytes per PE)",
                    Fault::kNone, ext < 0 ? ext : ext + len - 1);
        uint8_t* lp = m.mem_ + static_cast<size_t>(loc) * P;
        uint8_t* ep = m.ext_ + static_cast<size_t>(ext) * P;
        const size_t n = static_cast<size_t>(len) * P;
        // Only the active PEs' bytes cross the path; a masked PE's local
        // (xld) or external (xst) memory keeps its bytes.
        uint8_t* dst = Store ? ep : lp;
        const uint8_t* src = Store ? lp : ep;
        if (m.full_) {
            std::memcpy(dst, src, n);
        } else if (m.active_ > 0) {
            const uint8_t* mk = m.m_;
            for (size_t r = 0; r < n; r += P)
                for (size_t p = 0; p < P; ++p)
                    if (mk[p]) dst[r + p] = src[r + p];
        }
        if constexpr (Store)
            m.note_ext_write(static_cast<size_t>(ext) * P, static_cast<size_t>(ext) * P + n);
        m.extra_ =
            m.cfg_.costs.xfer_cycles(static_cast<uint64_t>(len), static_cast<uint64_t>(m.active_)) -
            m.cfg_.costs.xfer_setup;
        m.ext_bytes_ += static_cast<uint64_t>(len) * static_cast<uint64_t>(m.active_);
    }

    // rxl: rd(p) = ra(p - k); rxr: rd(p) = ra(p + k) (indices mod P). Every
    // PE drives the ring; only the register write is masked.
    template <bool Left, bool Full>
    IMAP_INLINE static void ring(Machine& m, const Decoded& d) {
        const size_t P = static_cast<size_t>(m.P_), S = m.S_;
        if (m.ring_) {
            m.ring_->shift(m.lanes_ + d.d, m.lanes_ + d.a, m.m_, m.P_, d.imm, Left);
            return;
        }
        ring_rotate<Left>(m.scratch_, m.lanes_ + d.a, P, static_cast<size_t>(d.imm));
        uint8_t* dst = m.lanes_ + d.d;
        const uint8_t* s = m.scratch_;
        const uint8_t* mk = m.m_;
        IMAP_LANES(S, p, dst[p] = Full ? s[p] : blend(lane_mask(mk[p]), s[p], dst[p]);)
    }

    // Any = OR of T over active PEs; otherwise AND of T over active PEs.
    // Padding lanes of M are 0, so they count as inactive.
    template <bool Any>
    IMAP_INLINE static uint32_t status(Machine& m) {
        if (m.status_) return m.status_->reduce(m.t_, m.m_, m.P_, Any);
        const size_t S = m.S_;
        const uint8_t* t = m.t_;
        const uint8_t* mk = m.m_;
        uint8_t acc = Any ? 0 : 1;
        if constexpr (Any)
            IMAP_LANES(S, p, acc = static_cast<uint8_t>(acc | (t[p] & mk[p]));)
        else
            IMAP_LANES(S, p, acc = static_cast<uint8_t>(acc & (t[p] | (mk[p] ^ 1u)));)
        return acc & 1u;
    }

    // Sets active_ and full_ from M (padding lanes are 0).
    IMAP_INLINE static void recount(Machine& m) {
        const size_t S = m.S_;
        const uint8_t* mk = m.m_;
        uint32_t n = 0;
        IMAP_LANES(S, p, n += mk[p];)
        m.active_ = static_cast<int>(n);
        m.full_ = m.active_ == m.P_;
    }

    static void branch(Machine& m, const Decoded& d, bool taken) {
        if (taken) {
            m.next_pc_ = d.aux;
            m.extra_ = m.cfg_.costs.branch_taken;
        }
    }

    // A timed camera (docs/isa.md 2.3): the vin waits until its pixels have
    // arrived; the wait is added to the instruction's cycles.
    static void camera_wait(Machine& m, int port, int y, int x) {
        if (!m.cfg_.board.camera_timed()) return;
        const int w = m.video_->input_width(port);
        if (w < 0)
            throw std::runtime_error(
                "the camera timing (camera_pixel_mhz) needs the image width, and this video "
                "port does not give it");
        const uint64_t ready = m.cfg_.camera_ready_cycle(w, y, x, m.P_);
        if (ready > m.cycles_) m.extra_ = ready - m.cycles_;
    }

    static void video(Machine& m, const Decoded& d, bool out) {
        const char* mn = out ? "vout" : "vin";
        const size_t P = static_cast<size_t>(m.P_);
        if (!m.video_) plain_fault(m, std::string(mn) + ": no video port attached to the machine");
        const int64_t addr = mem_addr(m, d, mn);
        const int64_t y = cpv(m, d.aux & 15u), x = cpv(m, d.aux >> 4);
        uint8_t* row = m.mem_ + static_cast<size_t>(addr) * P;
        try {
            const int port = static_cast<int>(d.d), yi = static_cast<int>(y),
                      xi = static_cast<int>(x);
            const uint32_t a = static_cast<uint32_t>(addr);
            if (out) {
                if (!m.video_->write_row(port, yi, xi, a, m.P_))
                    m.video_->write_line(port, yi, xi, row, m.P_);
            } else {
                camera_wait(m, port, yi, xi);
                if (!m.video_->read_row(port, yi, xi, a, m.P_)) {
                    m.video_->read_line(port, yi, xi, m.scratch_, m.P_);
                    std::memcpy(row, m.scratch_, P);
                }
            }
        } catch (const std::exception& e) {
            m.fault(std::string(mn) + " port " + std::to_string(d.d) + " line " +
                    std::to_string(y) + " column " + std::to_string(x) + ": " + e.what());
        }
    }

    static void end_of_program(Machine& m, const Decoded&) {
        m.fault("the PC ran past the end of the program (" + std::to_string(m.prog_.code.size()) +
                " instructions) without halt");
    }

    // Fixed: the machine has 256 lanes (S = 256, the board's size): the lane
    // loops get a constant trip count and unroll.
    template <Op O, bool Full, SimdPath Path, bool Fixed>
    IMAP_INLINE static void exec(Machine& m, const Decoded& d) {
        if constexpr (Fixed) {
            if (m.S_ != kFixedLanes) __builtin_unreachable();
        }
        constexpr Format F = format_of(O);
        [[maybe_unused]] const size_t P = static_cast<size_t>(m.P_);
        [[maybe_unused]] const size_t S = m.S_;
        [[maybe_unused]] auto& c = m.creg_;
        if constexpr (O == Op::CSEL || O == Op::TSEL) {
            select<Full>(m, d, O == Op::CSEL ? m.c_ : m.t_);
        } else if constexpr (F == Format::Rrr || O == Op::ROLC || O == Op::RORC) {
            alu<O, Full, false>(m, d);  // rolc / rorc: b lane unused (decoded as ra)
        } else if constexpr (F == Format::Rsh) {
            shift_imm<O, Full>(m, d);
        } else if constexpr (F == Format::Rri8) {
            alu<O, Full, true>(m, d);
        } else if constexpr (F == Format::Cmp) {
            cmp<O, Full, false>(m, d);
        } else if constexpr (F == Format::Cmpi) {
            cmp<O, Full, true>(m, d);
        } else if constexpr (O == Op::MOV) {
            write_masked<Full>(m, d.d, m.lanes_ + d.a);
        } else if constexpr (O == Op::LI) {
            write_masked_value<Full>(m, d.d, static_cast<uint8_t>(d.imm));
        } else if constexpr (O == Op::LC || O == Op::LCB) {
            write_masked_value<Full>(m, d.d, static_cast<uint8_t>(c[d.a] >> (8 * d.imm)));
        } else if constexpr (O == Op::PIDX) {
            write_masked<Full>(m, d.d, m.pidx_ + static_cast<size_t>(d.imm) * S);
        } else if constexpr (O == Op::SETC) {
            write_masked<Full>(m, d.d, m.c_);
        } else if constexpr (O == Op::SETT) {
            write_masked<Full>(m, d.d, m.t_);
        } else if constexpr (O == Op::TC || O == Op::TNOT) {
            tflag<Full, O == Op::TC>(m);
        } else if constexpr (O == Op::LD || O == Op::ST) {
            ldst<O == Op::ST, Full>(m, d);
        } else if constexpr (O == Op::LDX || O == Op::STX) {
            ldstx<O == Op::STX, Full, Path>(m, d);
        } else if constexpr (O == Op::XLD || O == Op::XST) {
            xfer<O == Op::XST>(m, d);
        } else if constexpr (O == Op::RXL || O == Op::RXR) {
            ring<O == Op::RXL, Full>(m, d);
        } else if constexpr (O == Op::MIF) {
            if (m.msp_ >= m.cfg_.mask_depth)
                plain_fault(m, "mif: mask stack overflow (mask_depth = " +
                                   std::to_string(m.cfg_.mask_depth) + ")");
            std::memcpy(m.mstack_ + static_cast<size_t>(m.msp_) * S, m.m_, S);
            ++m.msp_;
            uint8_t* mk = m.m_;
            const uint8_t* t = m.t_;
            IMAP_LANES(S, p, mk[p] = static_cast<uint8_t>(mk[p] & t[p]);)
            recount(m);
        } else if constexpr (O == Op::MELSE) {
            if (m.msp_ == 0) plain_fault(m, "melse: mask stack underflow (melse without mif)");
            const uint8_t* top = m.mstack_ + static_cast<size_t>(m.msp_ - 1) * S;
            uint8_t* mk = m.m_;
            IMAP_LANES(S, p, mk[p] = static_cast<uint8_t>(top[p] & (mk[p] ^ 1u));)
            recount(m);
        } else if constexpr (O == Op::MEND) {
            if (m.msp_ == 0) plain_fault(m, "mend: mask stack underflow (mend without mif)");
            --m.msp_;
            std::memcpy(m.m_, m.mstack_ + static_cast<size_t>(m.msp_) * S, S);
            recount(m);
        } else if constexpr (O == Op::MALL) {
            std::memset(m.m_, 1, P);
            m.msp_ = 0;
            m.active_ = m.P_;
            m.full_ = true;
        } else if constexpr (O == Op::RANY || O == Op::RALL) {
            c[d.d] = status<O == Op::RANY>(m);
        } else if constexpr (O == Op::VIN || O == Op::VOUT) {
            video(m, d, O == Op::VOUT);
        } else if constexpr (O == Op::NOP) {
        } else if constexpr (O == Op::HALT) {
            m.halted_ = true;
            m.next_pc_ = m.pc_;
        } else if constexpr (O == Op::PHASE) {
            m.phase_ = static_cast<uint32_t>(d.imm);
        } else if constexpr (O == Op::CLI) {
            c[d.d] = static_cast<uint32_t>(d.imm);
        } else if constexpr (O == Op::CMOV) {
            c[d.d] = c[d.a];
        } else if constexpr (F == Format::Ccc || F == Format::Cci || F == Format::Csh) {
            const uint32_t a = c[d.a];
            const uint32_t b = F == Format::Ccc ? c[d.b] : static_cast<uint32_t>(d.imm);
            uint32_t r = 0;
            if constexpr (O == Op::CADD || O == Op::CADDI)
                r = a + b;
            else if constexpr (O == Op::CSUB || O == Op::CSUBI)
                r = a - b;
            else if constexpr (O == Op::CAND || O == Op::CANDI)
                r = a & b;
            else if constexpr (O == Op::COR || O == Op::CORI)
                r = a | b;
            else if constexpr (O == Op::CXOR || O == Op::CXORI)
                r = a ^ b;
            else if constexpr (O == Op::CSHLI)
                r = a << b;
            else if constexpr (O == Op::CSHRI)
                r = a >> b;
            else if constexpr (O == Op::CSRAI)
                r = (a & 0x80000000u) ? ~(~a >> b) : a >> b;
            c[d.d] = r;
        } else if constexpr (O == Op::CLD || O == Op::CST) {
            const int64_t a = cpv(m, d.b) + d.imm;
            if (a < 0 || a >= kParamWords)
                m.fault(std::string(O == Op::CLD ? "cld" : "cst") + ": param block address " +
                            std::to_string(a) + " out of range 0.." +
                            std::to_string(kParamWords - 1),
                        Fault::kNone, a);
            if constexpr (O == Op::CLD)
                c[d.d] = m.params_[static_cast<size_t>(a)];
            else
                m.params_[static_cast<size_t>(a)] = c[d.d];
        } else if constexpr (O == Op::JMP) {
            branch(m, d, true);
        } else if constexpr (O == Op::BEQ) {
            branch(m, d, c[d.a] == c[d.b]);
        } else if constexpr (O == Op::BNE) {
            branch(m, d, c[d.a] != c[d.b]);
        } else if constexpr (O == Op::BLT) {
            branch(m, d, as_signed(c[d.a]) < as_signed(c[d.b]));
        } else if constexpr (O == Op::BGE) {
            branch(m, d, as_signed(c[d.a]) >= as_signed(c[d.b]));
        } else if constexpr (O == Op::BZ) {
            branch(m, d, c[d.a] == 0);
        } else if constexpr (O == Op::BNZ) {
            branch(m, d, c[d.a] != 0);
        } else if constexpr (O == Op::LOOP) {
            c[d.a] -= 1;
            branch(m, d, c[d.a] != 0);
        } else if constexpr (O == Op::CALL) {
            if (m.csp_ >= m.cfg_.call_depth)
                plain_fault(m, "call: return stack overflow (call_depth = " +
                                   std::to_string(m.cfg_.call_depth) + ")");
            m.cstack_[static_cast<size_t>(m.csp_++)] = m.pc_ + 1;
            branch(m, d, true);
        } else if constexpr (O == Op::RET) {
            if (m.csp_ == 0) plain_fault(m, "ret: return stack underflow (ret without call)");
            m.next_pc_ = m.cstack_[static_cast<size_t>(--m.csp_)];
            m.extra_ = m.cfg_.costs.branch_taken;
        } else {
            static_assert(O == Op::NOP, "opcode without semantics");
        }
    }
};

// ---------------------------------------------------------------------------
// The handler tables: one wrapper per path, identical bodies.

namespace {

template <Op O, bool Full, bool Fixed>
void exec_generic(Machine& m, const Decoded& d) {
    Exec::exec<O, Full, SimdPath::Generic, Fixed>(m, d);
}

#ifdef IMAP_HAVE_X86_PATHS
template <Op O, bool Full, bool Fixed>
IMAP_TARGET_AVX2 void exec_avx2(Machine& m, const Decoded& d) {
    Exec::exec<O, Full, SimdPath::Avx2, Fixed>(m, d);
}
template <Op O, bool Full, bool Fixed>
IMAP_TARGET_AVX512 void exec_avx512(Machine& m, const Decoded& d) {
    Exec::exec<O, Full, SimdPath::Avx512, Fixed>(m, d);
}
#endif

Handler generic_of(uint8_t code, bool full, bool fixed) {
    switch (code) {
#define IMAP_ISA_X(id, mn, code, fmt, cls, doc)                    \
    case code:                                                     \
        return fixed ? (full ? &exec_generic<Op::id, true, true>   \
                             : &exec_generic<Op::id, false, true>) \
                     : (full ? &exec_generic<Op::id, true, false>  \
                             : &exec_generic<Op::id, false, false>);
        IMAP_ISA_OPCODES(IMAP_ISA_X)
#undef IMAP_ISA_X
        default:
            return nullptr;
    }
}

#ifdef IMAP_HAVE_X86_PATHS
Handler avx2_of(uint8_t code, bool full, bool fixed) {
    switch (code) {
#define IMAP_ISA_X(id, mn, code, fmt, cls, doc)                                                \
    case code:                                                                                 \
        return fixed                                                                           \
                   ? (full ? &exec_avx2<Op::id, true, true> : &exec_avx2<Op::id, false, true>) \
                   : (full ? &exec_avx2<Op::id, true, false> : &exec_avx2<Op::id, false, false>);
        IMAP_ISA_OPCODES(IMAP_ISA_X)
#undef IMAP_ISA_X
        default:
            return nullptr;
    }
}
Handler avx512_of(uint8_t code, bool full, bool fixed) {
    switch (code) {
#define IMAP_ISA_X(id, mn, code, fmt, cls, doc)                                                    \
    case code:                                                                                     \
        return fixed                                                                               \
                   ? (full ? &exec_avx512<Op::id, true, true> : &exec_avx512<Op::id, false, true>) \
                   : (full ? &exec_avx512<Op::id, true, false>                                     \
                           : &exec_avx512<Op::id, false, false>);
        IMAP_ISA_OPCODES(IMAP_ISA_X)
#undef IMAP_ISA_X
        default:
            return nullptr;
    }
}
#endif

}  // namespace

namespace detail {

Handler handler_of(SimdPath path, uint8_t code, bool full, bool fixed) {
#ifdef IMAP_HAVE_X86_PATHS
    if (path == SimdPath::Avx512) return avx512_of(code, full, fixed);
    if (path == SimdPath::Avx2) return avx2_of(code, full, fixed);
#endif
    (void)path;
    return generic_of(code, full, fixed);
}

Handler end_of_program_handler() {
    return &Exec::end_of_program;
}

bool cpu_supports(SimdPath path) {
    switch (path) {
        case SimdPath::Generic:
            return true;
#ifdef IMAP_HAVE_X86_PATHS
        case SimdPath::Avx2:
            __builtin_cpu_init();
            return __builtin_cpu_supports("avx2");
        case SimdPath::Avx512:
            __builtin_cpu_init();
            return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                   __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq");
#endif
        default:
            return false;
    }
}

}  // namespace detail

}  // namespace imap::isa
