// Where a forward plan's pointer columns live (docs/firmware.md, sections 3
// and 4), from its passes, its fixed regions (plan_memory.cpp) and the
// memory sizes: each column on chip, in the pointer region or in line-buffer
// bytes already consumed, or spilled to the external memory (the fewest
// first columns that let the rest fit) and reloaded before the backtrack
// reaches it; the output line; with arrays of 2 to 5 PEs (`tiny`) every
// table in the external memory and three reload buffers.
#include <algorithm>
#include <sstream>

#include "plan_internal.hpp"

namespace imap::firmware::detail {

namespace {

// Bytes of a pass holding kind p's pointers (a shared pass computes the
// union of the kinds' ranges; a kind's pointers are the bytes up to its top).
int kind_bytes(const ForwardPlan& f, const ForwardPass& ps, int p) {
    if (ps.kind >= 0) return ps.kind == p ? ps.bytes : 0;
    if (ps.k > f.K[p]) return 0;
    return ceil_div(f.hi[p][ps.k] + f.lsh[p] - ps.jlo + 1, 4);
}

struct FreeMap {
    int mem = 0;
    std::vector<int> avail[2];  // first column from which an address may hold pointers
    std::vector<char> used[2];

    bool free_for(int p, int a, int k) const { return !used[p][a] && avail[p][a] <= k; }
    // Lowest address of `len` bytes free for every kind in `kinds` from column k.
    int find(int len, const std::vector<int>& kinds, int k, int from = 0) const {
        for (int a = from; a + len <= mem; ++a) {
            bool ok = true;
            for (int b = a; b < a + len && ok; ++b)
                for (int p : kinds) ok = ok && free_for(p, b, k);
            if (ok) return a;
        }
        return -1;
    }
};

// The memory free for pointers during the forward pass: the pointer region
// from column 1, each line-buffer byte (or window copy) once the last column
// that reads it is done.
FreeMap forward_free_map(const ForwardPlan& f, int mem) {
    FreeMap fm;
    fm.mem = mem;
    for (int p = 0; p < 2; ++p) {
        fm.avail[p].assign(mem, kNever);
        fm.used[p].assign(mem, 0);
        for (int a = f.preg; a < mem; ++a) fm.avail[p][a] = 1;
        if (f.agg > 0) {
            // the window copies: Rx[m], Lx[m] (and codes) die after column m + agg
            std::vector<int> offs = {0};
            if (f.kc > 0) offs.push_back(f.cxo);
            if (f.bt) {
                offs.push_back(f.blo);
                offs.push_back(f.bhi);
            }
            for (int off : offs) {
                for (int m = 1 - f.agg; m <= f.kr + f.agg; ++m)
                    fm.avail[p][f.rbr - m + off] = std::max(1, m + f.agg + 1);
                for (int m = 1 - f.agg; m <= f.kl + f.agg; ++m)
                    fm.avail[p][f.rbl + m + off] = std::max(1, m + f.agg + 1);
            }
            continue;
        }
        for (int i = 0; i <= f.kr; ++i)
            fm.avail[p][f.rp_addr(i)] = i + 1;  // R'[i] dies after column i
        for (int i = 0; i < f.lsh[p]; ++i) fm.avail[p][f.rb + 1 + i] = 1;  // below its L'
        for (int i = 0; i <= f.kl - f.lsh[p]; ++i)
            fm.avail[p][f.lp_addr(i, p)] = i + 1;  // L'[i] dies after column i
    }
    return fm;
}

// Passes [i, j) of one column write their pointer bytes at local address
// `addr`; each kind's column is then at local address `local` or external
// address `ext` (-1: neither). `take(p, a, b)` sees kind p's pointers in
// bytes a .. b - 1 of the column (a split pass's late kind starts a > 0:
// the bytes below hold values nothing reads).
template <class Take>
void assign_column(ForwardPlan& f, size_t i, size_t j, int addr, int local, int ext, Take&& take) {
    const int k = f.passes[i].k;
    for (size_t q = i; q < j; ++q) {
        f.passes[q].addr = addr;
        for (int p = 0; p < f.kinds; ++p) {
            const int b = kind_bytes(f, f.passes[q], p);
            if (b == 0) continue;
            const ForwardPass& ps = f.passes[q];
            take(p, ps.split > 0 && ps.late == p ? ps.split / 4 : 0, b);
            f.ptr[p][k] = {local, f.passes[q].jlo - f.lsh[p], b, ext};
        }
    }
}

// The forward pass's pointer bytes: columns 1..spill staged at the start of
// the pointer region and spilled in blocks (xst), the others on chip where
// `fm` has room for every kind the column runs on.
bool place_forward(ForwardPlan& f, FreeMap& fm, int mem, int spill) {
    for (int p = 0; p < 2; ++p) f.ptr[p].assign(f.kmax + 1, PointerColumn{});
    f.spills.clear();
    f.reloads.clear();
    const int stage_cap = std::min(mem - f.preg, 4096);
    int stage_off = 0, ext = 0, block_ext = 0;
    // One xst of the staged columns, after pass `after`.
    auto spill_block = [&](int after) {
        f.spills.push_back({f.preg, block_ext, stage_off, after});
        block_ext = ext;
        stage_off = 0;
    };
    size_t i = 0;
    while (i < f.passes.size()) {
        const int k = f.passes[i].k;
        size_t j = i;
        int size = 0;
        while (j < f.passes.size() && f.passes[j].k == k)
            size = std::max(size, f.passes[j++].bytes);
        std::vector<int> kinds;
        for (int p = 0; p < f.kinds; ++p)
            if (k <= f.K[p]) kinds.push_back(p);
        if (k <= spill) {
            if (size > stage_cap) return false;
            if (stage_off + size > stage_cap) spill_block(static_cast<int>(i) - 1);
            assign_column(f, i, j, f.preg + stage_off, -1, ext, [](int, int, int) {});
            stage_off += size;
            ext += size;
            if (k == spill) spill_block(static_cast<int>(j) - 1);
        } else {
            const int a = fm.find(size, kinds, k);
            if (a < 0) return false;
            assign_column(f, i, j, a, a, -1, [&](int p, int from, int b) {
                for (int x = a + from; x < a + b; ++x) fm.used[p][x] = 1;
            });
            // A pass writes `size` bytes for every kind it runs on; bytes
            // beyond a kind's own pointers are free for that kind afterwards.
        }
        i = j;
    }
    f.ext_needed = ext;
    return true;
}

// The step-synchronous backtrack's column table (ForwardPlan::bstep_tab),
// when every column is on chip, each kind has its columns 1..K without a
// gap, column indices fit a byte and 2 * (kmax + 1) bytes are free of the
// map and the columns; returns the end of the table (0 if none).
int place_step_table(ForwardPlan& f, const FreeMap& fm, int mem) {
    f.bstep_tab = -1;
    if (f.tiny || f.kmax > 255 || !f.reloads.empty() || !f.spills.empty()) return 0;
    for (int p = 0; p < f.kinds; ++p) {
        f.bstep_a[p].assign(f.kmax + 1, 0);
        f.bstep_k0[p] = std::min(f.K[p], f.kmax);
        for (int k = 1; k <= f.bstep_k0[p]; ++k) {
            const PointerColumn& c = f.ptr[p][k];
            if (c.bytes == 0 || c.ext >= 0 || c.addr < 0) return 0;
            f.bstep_a[p][k] = (4 * c.addr - c.base) & 0xFFFF;
        }
    }
    FreeMap rm = fm;
    for (int p = 0; p < 2; ++p)
        for (int x = f.map; x < f.map + f.N && x < mem; ++x) rm.used[p][x] = 1;
    const int len = 2 * (f.kmax + 1);
    const int a = rm.find(len, {0, 1}, 0);
    if (a < 0) return 0;
    f.bstep_tab = a;
    return a + len;
}

// After the forward pass: the output line (free of every on-chip column),
// then each spilled column reloaded just before the backtrack reaches it,
// into memory free of the map and of the on-chip columns still ahead
// (xld writes every PE, so free for every kind). Sets f.mem_needed.
bool place_backtrack(ForwardPlan& f, FreeMap& fm, int mem, int spill) {
    for (int p = 0; p < 2; ++p)
        for (int a = 0; a < mem; ++a) fm.avail[p][a] = a < f.kblk + f.kbs ? kNever : 0;
    const std::vector<int> all = {0, 1};
    f.map = fm.find(f.N, all, 0);
    if (f.map < 0) return false;
    int top = std::max(f.preg, f.map + f.N);
    for (const Transfer& t : f.spills) top = std::max(top, t.local + t.len);
    if (spill > 0) {
        FreeMap rm = fm;  // used: on-chip columns; the map is added below
        for (int p = 0; p < 2; ++p)
            for (int x = f.map; x < f.map + f.N; ++x) rm.used[p][x] = 1;
        // column -> its on-chip bytes per kind (to release them as the backtrack passes)
        for (int k = f.kmax; k >= 1; --k) {
            if (k > spill) {
                for (int p = 0; p < f.kinds; ++p) {
                    const PointerColumn& c = f.ptr[p][k];
                    if (c.bytes == 0 || c.ext >= 0) continue;
                    for (int x = c.addr; x < c.addr + c.bytes; ++x) rm.used[p][x] = 0;
                }
                continue;
            }
            const ColumnBytes col = column_bytes(f, k);
            if (col.ext < 0 || col.size == 0) continue;
            const int a = rm.find(col.size, all, 0);
            if (a < 0) return false;
            f.reloads.push_back({a, col.ext, col.size, k});
            for (int p = 0; p < f.kinds; ++p)
                if (f.ptr[p][k].bytes > 0) f.ptr[p][k].addr = a;
            top = std::max(top, a + col.size);
        }
    }
    if (spill == 0) top = std::max(top, place_step_table(f, fm, mem));
    // Highest local address in use by the DP.
    for (int p = 0; p < 2; ++p)
        for (int a = mem - 1; a >= 0; --a)
            if (fm.used[p][a]) {
                top = std::max(top, a + 1);
                break;
            }
    f.mem_needed = top;
    return true;
}

// Places the pointer columns: the first `spill` columns go to the external
// memory (staged at the start of the pointer region), the others on chip;
// false if they do not fit.
bool place_pointers(ForwardPlan& f, int mem, int spill) {
    FreeMap fm = forward_free_map(f, mem);
    return place_forward(f, fm, mem, spill) && place_backtrack(f, fm, mem, spill);
}

// Every pointer table in the external memory (three rotating slots of
// ext_table bytes), the backtrack voting from three reloaded columns
// (docs/firmware.md, section 4: arrays of 2 to 5 PEs).
bool place_tiny(ForwardPlan& f, int mem) {
    if (!place_pointers(f, mem, f.kmax)) return false;
    // place_pointers reloaded each column into the lowest free bytes: now
    // one buffer for the own column and two for the neighbours' columns.
    int size = 0;
    for (const ForwardPass& ps : f.passes) size = std::max(size, ps.bytes);
    f.reloads.clear();
    const int lo = f.kblk + f.kbs;
    auto overlaps_map = [&](int a, int n) { return a < f.map + f.N && f.map < a + n; };
    int a = lo, bufs[3], got = 0;
    while (got < 3 && a + size <= mem) {
        if (overlaps_map(a, size)) {
            a = f.map + f.N;
            continue;
        }
        bufs[got++] = a;
        a += size;
    }
    if (got < 3) return false;
    f.tiny_buf[0] = bufs[0];
    f.tiny_buf[1] = bufs[1];
    f.tiny_buf[2] = bufs[2];
    for (int p = 0; p < f.kinds; ++p)
        for (int k = 1; k <= f.kmax; ++k)
            if (f.ptr[p][k].bytes > 0) f.ptr[p][k].addr = bufs[0];
    f.ext_table = static_cast<int>(f.ext_needed);
    f.ext_needed = 3 * int64_t{f.ext_table};
    f.mem_needed = std::max(f.mem_needed, bufs[2] + size);
    f.tiny = true;
    return true;
}

// The error names the least local memory that would do: found by the same
// placement `fits` (it is monotone in the memory size).
template <class Fits>
FirmwareError too_small(int mem, const char* what, Fits&& fits) {
    int lo = mem + 1, hi = 1 << 16;
    std::ostringstream os;
    os << "does not fit: ";
    if (fits(hi)) {
        while (lo < hi) {
            const int mid = lo + (hi - lo) / 2;
            if (fits(mid))
                hi = mid;
            else
                lo = mid + 1;
        }
        os << "needs at least " << lo << " bytes of local memory per PE for " << what;
    } else {
        os << "needs more than " << hi << " bytes of local memory per PE for " << what;
    }
    os << " (have " << mem << ", mem_bytes)";
    return FirmwareError(os.str());
}

}  // namespace

ColumnBytes column_bytes(const ForwardPlan& f, int k) {
    ColumnBytes c;
    for (int p = 0; p < f.kinds; ++p)
        if (f.ptr[p][k].bytes > 0) c.ext = f.ptr[p][k].ext;
    for (const ForwardPass& ps : f.passes)
        if (ps.k == k) c.size = std::max(c.size, ps.bytes);
    return c;
}

void place_columns(ForwardPlan& f, const isa::MachineConfig& cfg, bool tiny) {
    const int mem = plan_mem(cfg);
    if (tiny) {
        if (!place_tiny(f, mem))
            throw too_small(mem, "the line buffers, costs, output line and three pointer columns",
                            [&](int m) { return place_tiny(f, m); });
    } else if (!place_pointers(f, mem, 0)) {
        // The fewest spilled columns (the first ones) that let the rest fit.
        int lo = 1, hi = f.kmax;
        if (!place_pointers(f, mem, hi))
            throw too_small(mem, "the line buffers, costs, output line and one pointer column",
                            [&](int m) { return place_pointers(f, m, f.kmax); });
        while (lo < hi) {
            const int mid = lo + (hi - lo) / 2;
            if (place_pointers(f, mem, mid))
                hi = mid;
            else
                lo = mid + 1;
        }
        place_pointers(f, mem, lo);
    }
    if (f.ext_needed > int64_t{cfg.ext_bytes}) {
        std::ostringstream os;
        os << "does not fit: needs " << f.ext_needed
           << " bytes of external memory per PE for the spilled pointer columns (have "
           << cfg.ext_bytes << ", ext_bytes)";
        throw FirmwareError(os.str());
    }
}

}  // namespace imap::firmware::detail
