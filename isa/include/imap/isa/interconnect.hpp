// The two array-wide paths of the machine, written once: the shift ring
// (rxl / rxr) and the status reduction over the mask bus (rany / rall).
//
// The executor uses these functions directly (built-in path). A model that
// makes the ring or the mask bus a component of its own (the TLM model's
// top.ring and top.maskbus) implements RingPort / StatusPort by calling the
// same functions, and attaches itself with Machine::set_ring / set_status;
// the machine then makes one virtual call per ring or status instruction
// (never one per lane). The semantics therefore cannot diverge.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace imap::isa {

#if defined(__GNUC__) && !defined(__clang__)
#define IMAP_ISA_IVDEP _Pragma("GCC ivdep")
#else
#define IMAP_ISA_IVDEP
#endif

// The shift ring, in two halves (the executor calls them separately so that
// no lane pointer lives across the copies; ring_shift below is both).
// ring_rotate: s = src rotated by hops mod P, towards higher PE indices
// (rxl) or lower ones (rxr). ring_write: dst = M ? s : dst.
template <bool TowardsHigher>
inline void ring_rotate(uint8_t* s, const uint8_t* src, size_t P, size_t hops) {
    const size_t k = hops % P;
    if constexpr (TowardsHigher) {
        std::memcpy(s + k, src, P - k);
        std::memcpy(s, src + P - k, k);
    } else {
        std::memcpy(s, src + k, P - k);
        std::memcpy(s + P - k, src, k);
    }
}
inline void ring_write(uint8_t* dst, const uint8_t* s, const uint8_t* mask, size_t P) {
    IMAP_ISA_IVDEP
    for (size_t p = 0; p < P; ++p) {
        // M ? s : dst, branch-free: ((s ^ dst) & -M) ^ dst
        const uint8_t km = static_cast<uint8_t>(-mask[p]);
        dst[p] = static_cast<uint8_t>(((s[p] ^ dst[p]) & km) ^ dst[p]);
    }
}
// dst = M ? shifted src : dst over P lanes, where the shifted row is
//   TowardsHigher (rxl): s[p] = src[(p - hops) mod P]  (data moves up)
//   otherwise     (rxr): s[p] = src[(p + hops) mod P]  (data moves down)
// Every PE drives the ring (the mask only gates the write of dst). `scratch`
// is P bytes disjoint from the other rows; dst may be src.
template <bool TowardsHigher>
inline void ring_shift(uint8_t* dst, const uint8_t* src, const uint8_t* mask, uint8_t* scratch,
                       size_t P, size_t hops) {
    ring_rotate<TowardsHigher>(scratch, src, P, hops);
    ring_write(dst, scratch, mask, P);
}
inline void ring_shift(uint8_t* dst, const uint8_t* src, const uint8_t* mask, uint8_t* scratch,
                       size_t P, size_t hops, bool towards_higher) {
    if (towards_higher)
        ring_shift<true>(dst, src, mask, scratch, P, hops);
    else
        ring_shift<false>(dst, src, mask, scratch, P, hops);
}

// The status reduction: Any = OR of T over active PEs (0 when none);
// otherwise AND of T over active PEs (1 when none).
template <bool Any>
inline uint32_t status_reduce(const uint8_t* t, const uint8_t* mask, size_t P) {
    if constexpr (Any) {
        uint8_t acc = 0;
        for (size_t p = 0; p < P; ++p) acc = static_cast<uint8_t>(acc | (t[p] & mask[p]));
        return acc;
    } else {
        uint8_t acc = 1;
        for (size_t p = 0; p < P; ++p) acc = static_cast<uint8_t>(acc & (t[p] | (mask[p] ^ 1u)));
        return acc;
    }
}
inline uint32_t status_reduce(const uint8_t* t, const uint8_t* mask, size_t P, bool any) {
    return any ? status_reduce<true>(t, mask, P) : status_reduce<false>(t, mask, P);
}

#undef IMAP_ISA_IVDEP

// The shift ring as a component. Called once per rxl / rxr with the lanes of
// rd (dst), ra (src) and M; must compute exactly ring_shift().
class RingPort {
  public:
    virtual ~RingPort() = default;
    // hops = the instruction's k (1..65535, not reduced modulo P).
    virtual void shift(uint8_t* dst, const uint8_t* src, const uint8_t* mask, int P, int hops,
                       bool towards_higher) = 0;
};

// The status reduction of the mask bus as a component. Called once per
// rany / rall; must return exactly status_reduce().
class StatusPort {
  public:
    virtual ~StatusPort() = default;
    virtual uint32_t reduce(const uint8_t* t, const uint8_t* mask, int P, bool any) = 0;
};

}  // namespace imap::isa
