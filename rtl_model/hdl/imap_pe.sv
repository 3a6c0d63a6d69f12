`include "imap_mutants.svh"
`include "imap_assert.svh"
// One processing element (docs/isa.md 1.1, 4, 4.1): register file, 8-bit
// adder with carry, comparator and min/max, the shifter, the C / T / M flags,
// the mask stack, write-back gated by M, and the local memory (docs/rtl.md,
// "The PE's local memory").
//
// The PE obeys the control word broadcast by the CP (imap_pkg::cw_t); it
// does nothing in a cycle without cw.act. Its outputs are registers (row_q:
// the memory's read registers through its write-first bypass), so a cycle
// of the whole array is one clocked process per PE. Operands are read in
// the last cycle of an instruction (commit) from the register file, which
// does not change while an instruction is in execute. Four things are read
// one edge earlier, at the edge where the next instruction enters execute
// (cw.pre): the ring source register (rxl / rxr), the per-PE address (ldx /
// stx), and a row of the local memory: at the per-PE address for ldx, at
// the broadcast address for ld, vout and xst. ld and ldx take byte 0 of
// that row at commit. Those preloads take what is written at that same
// edge from the bypasses.
//
// The local memory is XROWS (8) byte banks, byte a in bank a mod 8 at index
// a / 8, each a synchronous RAM of one read and one write port (the shape
// synthesis maps to a block RAM): read only at preload edges and at the
// row-read cycles of xst (the XROWS bytes from any byte address, one per
// bank), written by one source per edge (one st / stx byte, or the up to
// XROWS bytes of a vin / xld row). A byte written at the read edge reads as
// written (one bypass register per bank).
//
// Coding rule: every read of the register file and of a memory bank comes
// before any write of it in the process (the writes are blocking: nothing
// outside this process reads them), so a read sees the state as the edge
// found it and every bypass is explicit.
`include "imap_ports.svh"
module imap_pe
#(
    parameter int NREGS = 16,
    parameter int MEM_BYTES  /*verilator public*/ = 1024,  // the backdoor reads it
    parameter int MASK_DEPTH = 8,
    parameter int XROWS = 8
) (
    input logic clk,
    `IMAP_MUTANT_PORT
    input imap_pkg::cw_t cw  /*verilator public_flat_rd*/,
    input imap_pkg::cwx_t cwx  /*verilator public_flat_rd*/,
    input logic [31:0] cw_pre  /*verilator public_flat_rd*/,  // preload base / row address
    input logic [15:0] pe_index  /*verilator public_flat_rd*/,
    input logic [7:0] nb_lo  /*verilator public_flat_rd*/,  // ring: value of PE index-1
    input logic [7:0] nb_hi  /*verilator public_flat_rd*/,  // ring: value of PE index+1
    input logic [XROWS*8-1:0] row_in  /*verilator public_flat_rd*/,  // row bus (vin / xld)
    output logic [7:0] ring_q  /*verilator public_flat_rd*/,  // ring register, to both neighbours
    output logic [2:0] st_q  /*verilator public_flat_rd*/,  // to the mask bus: {oob, T, M}
    output logic [XROWS*8-1:0] row_q  /*verilator public_flat_rd*/,  // row read port (vout / xst)
    output logic [15:0] xoff_q  // preloaded per-PE offset rb:ra (ldx / stx fault report)
);

  /*verilator no_inline_module*/
  // The state elements marked public_flat_rw are the testbench's backdoor
  // (final-state readout, clearing between programs): simulation only.
  /* verilator lint_off BLKSEQ */

  localparam int AW = $clog2(MEM_BYTES > 1 ? MEM_BYTES : 2);
  localparam int RW = $clog2(NREGS > 1 ? NREGS : 2);
  localparam int SM = 0, ST = 1, SOOB = 2;  // bits of st_q

  localparam int DEPTH = (MEM_BYTES + 7) / 8;  // bytes per bank
  localparam int IW = $clog2(DEPTH > 1 ? DEPTH : 2);
  localparam int AI = AW > 3 ? AW : 3;  // byte address width inside (at least the bank bits)

`ifndef SYNTHESIS
  // the memory is eight byte banks (bank0 .. bank7), one per byte of a row
  if (XROWS != 8) begin : g_xrows
    $fatal(1, "imap_pe: XROWS is %0d; the memory's eight byte banks need 8", XROWS);
  end
`endif

  logic [7:0] regs[NREGS] /*verilator public_flat_rw*/;
  // the local memory: bank k holds the bytes at addresses k, k + 8, k + 16, ...
  logic [7:0] bank0[DEPTH] /*verilator public_flat_rw*/;
  logic [7:0] bank1[DEPTH] /*verilator public_flat_rw*/;
  logic [7:0] bank2[DEPTH] /*verilator public_flat_rw*/;
  logic [7:0] bank3[DEPTH] /*verilator public_flat_rw*/;
  logic [7:0] bank4[DEPTH] /*verilator public_flat_rw*/;
  logic [7:0] bank5[DEPTH] /*verilator public_flat_rw*/;
  logic [7:0] bank6[DEPTH] /*verilator public_flat_rw*/;
  logic [7:0] bank7[DEPTH] /*verilator public_flat_rw*/;
  logic [63:0] bq;  // each bank's read register (bank k: bits 8k+7..8k)
  logic [63:0] bd;  // each bank's byte written at the read edge
  logic [7:0] byp;  // bank k: the byte written at the read edge is the one read
  logic [2:0] rlo_q;  // bank of byte 0 of the row read
  logic [63:0] rowm;  // (row_q: the banks' bytes through their bypass)
  logic c_q /*verilator public_flat_rd*/;
  logic [MASK_DEPTH-1:0] mstk /*verilator public_flat_rd*/;  // saved M values, top at bit 0
  logic [AW-1:0] xaddr_q;  // preloaded per-PE address
  logic [7:0] sh_acc;  // shifter: value being shifted
  logic [2:0] sh_rem;  // shifter: bits still to shift
  logic sh_c;  // shifter: last bit shifted out

  // Temporaries of the clocked process (set at its start in every cycle).
  imap_pkg::cw_t w;
  imap_pkg::cwx_t wx;
  logic [7:0] a, b, res, lo, hi, mval;
  logic [8:0] sum;
  logic cn, tn, mn, act, wb, mwe, oob, rw;
  logic [2:0] s;
  logic [AW-1:0] ma;
  logic [33:0] xa;
  // the memory ports of this edge: read (mre: XROWS bytes from mra), write
  // (byte i of wdat to wad + i for each wen[i])
  logic mre;
  logic [AI-1:0] mra, wad;
  logic [7:0] wen;
  logic [63:0] wdat;
  logic [7:0] wenb;  // the write enables in bank order (bank k: wenb[k])
  logic [63:0] wdatb;  // the write bytes in bank order
  logic [IW-1:0] rx, wx_;  // one bank's read / write index
`ifndef SYNTHESIS
  logic pre_ok;  // a_pe_preload
  logic chk_q;  // a row was read at the last edge (a_pe_preload, memory part)
  logic [AI-1:0] chk_ra;  // ... from this address
  logic [7:0] chk_in;  // bank k's byte of that row lies inside the memory
  logic [IW-1:0] chk_x[8];  // ... at this index
`endif

  // The row read (row_q): byte i from bank (rlo_q + i) mod 8, through its
  // bypass.
  always_comb begin
    rowm = bq;
    if (byp != 8'h00)
      for (int k = 0; k < 8; k++) if (byp[k]) rowm[k*8+:8] = bd[k*8+:8];
    // byte i from bank (rlo_q + i) mod 8: rotate right by rlo_q bytes
    // (a shift by 64 gives 0)
    row_q = (rowm >> {rlo_q, 3'b000}) | (rowm << (7'd64 - {1'b0, rlo_q, 3'b000}));
  end

  // The index in bank k of the row that starts at byte address x: the
  // row's bytes x .. x+7 are one per bank, byte a in bank a mod 8 at a / 8.
  function automatic [IW-1:0] bank_index(input [AI-1:0] x, input [2:0] k);
    bank_index = IW'(x >> 3) + IW'(k < x[2:0]);
  endfunction

  // One bank's ports at this edge (K: its number, B: its array). The read
  // comes before the write (the RAM reads the byte as the edge found it; 'x
  // on a read of the byte being written: the bypass register gives it).
`define IMAP_PE_BANK(K, B) \
  rx = bank_index(mra, 3'(K)); \
  wx_ = bank_index(wad, 3'(K)); \
  if (mre) begin \
    bq[K*8+:8] <= (wenb[K] && wx_ == rx) ? 8'hxx : B[rx]; \
    byp[K] <= wenb[K] && wx_ == rx && !`IMAP_MUT(16); \
    bd[K*8+:8] <= wdatb[K*8+:8]; \
  end \
  if (wenb[K]) B[wx_] = wdatb[K*8+:8];

  always_ff @(posedge clk) begin

    // Every temporary is set before the activity test (lets the simulator
    // keep them in machine registers).
    w = cw;
    wx = cwx;
    {a, b, res, lo, hi, mval} = '0;
    sum = '0;
    {cn, tn, mn, act, wb, mwe, oob, rw} = '0;
    s = '0;
    ma = '0;
    xa = '0;
    {mre, mra, wad, wen, wdat} = '0;
    {wenb, wdatb, rx, wx_} = '0;
`ifndef SYNTHESIS
    // a_pe_preload, memory part: a row byte read at the last edge equals the
    // bank's byte as that edge left it (before this edge's writes)
    if (chk_q) begin
      for (int k = 0; k < 8; k++) begin
        chk_x[k] = bank_index(chk_ra, 3'(k));
        chk_in[k] = 32'(chk_ra) + 32'(3'(3'(k) - chk_ra[2:0])) < 32'(MEM_BYTES);
      end
      pre_ok = 1'b1;
      if (chk_in[0]) pre_ok = pre_ok && (byp[0] ? bd[7:0] : bq[7:0]) == bank0[chk_x[0]];
      if (chk_in[1]) pre_ok = pre_ok && (byp[1] ? bd[15:8] : bq[15:8]) == bank1[chk_x[1]];
      if (chk_in[2]) pre_ok = pre_ok && (byp[2] ? bd[23:16] : bq[23:16]) == bank2[chk_x[2]];
      if (chk_in[3]) pre_ok = pre_ok && (byp[3] ? bd[31:24] : bq[31:24]) == bank3[chk_x[3]];
      if (chk_in[4]) pre_ok = pre_ok && (byp[4] ? bd[39:32] : bq[39:32]) == bank4[chk_x[4]];
      if (chk_in[5]) pre_ok = pre_ok && (byp[5] ? bd[47:40] : bq[47:40]) == bank5[chk_x[5]];
      if (chk_in[6]) pre_ok = pre_ok && (byp[6] ? bd[55:48] : bq[55:48]) == bank6[chk_x[6]];
      if (chk_in[7]) pre_ok = pre_ok && (byp[7] ? bd[63:56] : bq[63:56]) == bank7[chk_x[7]];
      a_pe_preload_mem :
      assert (pre_ok)
      else `IMAP_FAIL(a_pe_preload, pe_index);
    end
    chk_q <= 1'b0;
`endif
    if (w.act) begin
      act = st_q[SM];

      // ---- 1. preload reads (before any write of this edge)
      if (w.pre != imap_pkg::PRE_NONE || w.row == imap_pkg::ROW_READ) begin
        lo = regs[wx.pre_ra[RW-1:0]];
        hi = regs[wx.pre_rb[RW-1:0]];
      end

      // ---- 2. shifter pass (at most shift_bits bits) / ring hop
      if (w.first) begin
        sh_acc = regs[w.ra[RW-1:0]];
        sh_rem = w.bimm ? w.imm[2:0] : regs[w.rb[RW-1:0]][2:0];
        sh_c = c_q;
      end
      if (w.step) begin
        if (w.fn == imap_pkg::F_RING) ring_q <= w.up ? nb_lo : nb_hi;
        else if (sh_rem != 3'd0) begin
          s = (sh_rem < w.sbits) ? sh_rem : w.sbits;
          if (w.fn == imap_pkg::F_SHL) begin
            sh_c = sh_acc[3'(4'd8 - {1'b0, s})];
            sh_acc = sh_acc << s;
          end else begin
            sh_c = `IMAP_MUT(7) ? sh_acc[s] : sh_acc[s-3'd1];
            sh_acc = sh_acc >> s;
          end
          sh_rem = sh_rem - s;
        end
      end

      // ---- 3. execute and write back (active PEs; mask commands: all PEs)
      if (w.commit) begin
        a = regs[w.ra[RW-1:0]];
        b = w.bimm ? w.imm : regs[w.rb[RW-1:0]];
        res = a;
        cn = c_q;
        tn = st_q[ST];
        mn = st_q[SM];
        case (w.fn)
          imap_pkg::F_ADD: begin
            sum = {1'b0, a} + {1'b0, b};
            res = sum[7:0];
            cn = sum[8];
          end
          imap_pkg::F_ADC: begin
            sum = {1'b0, a} + {1'b0, b} + {8'h00, c_q};
            res = sum[7:0];
            cn = sum[8];
            if (`IMAP_MUT(1)) cn = ({1'b0, a} + {1'b0, b}) > 9'd255;
          end
          imap_pkg::F_SUB: begin
            sum = {1'b0, a} - {1'b0, b};
            res = sum[7:0];
            cn = sum[8];
          end
          imap_pkg::F_SBC: begin
            sum = {1'b0, a} - {1'b0, b} - {8'h00, c_q};
            res = sum[7:0];
            cn = sum[8];
          end
          imap_pkg::F_AND: res = a & b;
          imap_pkg::F_OR: res = a | b;
          imap_pkg::F_XOR: res = a ^ b;
          imap_pkg::F_MIN: res = (a < b) ? a : b;
          imap_pkg::F_MAX: res = (a > b) ? a : b;
          imap_pkg::F_PASSB: res = b;
          imap_pkg::F_PIDX:
          res = (w.imm[1:0] == 2'd0) ? pe_index[7:0] : (w.imm[1:0] == 2'd1) ? pe_index[15:8] : 8'h00;
          imap_pkg::F_SETC: res = {7'b0, c_q};
          imap_pkg::F_SETT: res = {7'b0, st_q[ST]};
          imap_pkg::F_CSEL: res = c_q ? a : b;
          imap_pkg::F_TSEL: res = st_q[ST] ? a : b;
          imap_pkg::F_ROLC: begin
            res = {a[6:0], c_q};
            cn = a[7];
          end
          imap_pkg::F_RORC: begin
            res = {c_q, a[7:1]};
            cn = a[0];
          end
          imap_pkg::F_SHL, imap_pkg::F_SHR: begin
            res = sh_acc;
            cn = sh_c;
          end
          imap_pkg::F_CMP:
          case (w.cmp)
            imap_pkg::CMP_EQ: tn = (a == b);
            imap_pkg::CMP_NE: tn = (a != b);
            imap_pkg::CMP_LT: tn = (a < b);
            imap_pkg::CMP_LE: tn = (a <= b);
            imap_pkg::CMP_GT: tn = (a > b);
            imap_pkg::CMP_GE: tn = (a >= b);
            imap_pkg::CMP_C: tn = c_q;
            default: tn = ~st_q[ST];
          endcase
          // the byte read at the edge where ld / ldx entered execute
          imap_pkg::F_LD, imap_pkg::F_LDX: res = row_q[7:0];
          imap_pkg::F_ST: begin
            mwe = act;
            ma = wx.addr[AW-1:0];
            mval = regs[w.rd[RW-1:0]];
          end
          imap_pkg::F_STX: begin
            mwe = act;
            ma = xaddr_q;
            mval = regs[w.rd[RW-1:0]];
          end
          imap_pkg::F_RING: res = w.up ? nb_lo : nb_hi;
          default: ;
        endcase
        case (w.mask)
          imap_pkg::MK_IF: begin
            mn = st_q[SM] & st_q[ST];
            mstk = (mstk << 1) | MASK_DEPTH'(st_q[SM]);
          end
          imap_pkg::MK_ELSE: mn = (mstk[0] | `IMAP_MUT(11)) & ~st_q[SM];
          imap_pkg::MK_END: begin
            mn = mstk[0];
            mstk = mstk >> 1;
          end
          imap_pkg::MK_ALL: begin
            mn = 1'b1;
            mstk = '0;
          end
          default: ;
        endcase
        wb = (act || (`IMAP_MUT(2) && w.fn == imap_pkg::F_SUB)) && w.rd_we;
        if (wb) regs[w.rd[RW-1:0]] = res;
        if (act && w.c_we) c_q = cn;
        if (!(act && w.t_we)) tn = st_q[ST];
        st_q <= {st_q[SOOB], tn, mn};
`ifndef SYNTHESIS
        // a masked PE writes nothing back: no register, no memory byte
        a_pe_masked_wb :
        assert (act || !(wb || mwe))
        else `IMAP_FAIL(a_pe_masked_wb, pe_index);
        // mif / melse: a PE is active inside the block only if it was
        // active where the block opened (the saved M on top of the stack)
        if (w.mask == imap_pkg::MK_IF || w.mask == imap_pkg::MK_ELSE)
          a_pe_mask_nest :
          assert (!mn || mstk[0])
          else `IMAP_FAIL(a_pe_mask_nest, pe_index);
`endif
      end

      // ---- 4. row bus: rows written (vin on every PE, xld on the active PEs)
      rw = (w.row == imap_pkg::ROW_WRITE) && (!w.rowm || st_q[SM] || `IMAP_MUT(13));
`ifndef SYNTHESIS
      // xld writes its rows on the active PEs only
      a_pe_masked_row :
      assert (!(rw && w.rowm) || st_q[SM])
      else `IMAP_FAIL(a_pe_masked_row, pe_index);
`endif
`ifndef SYNTHESIS
      // the memory has one write port: a st / stx byte or the rows of the
      // instruction in execute at an edge, never both
      a_pe_mem_write :
      assert (!(mwe && rw))
      else `IMAP_FAIL(a_pe_mem_write, pe_index);
`endif
      if (mwe) begin
        wad = AI'(ma);
        wen = 8'h01;
        wdat = {56'h0, mval};
      end else if (rw) begin
        wad = AI'(wx.addr[AW-1:0]);
        for (int i = 0; i < 8; i++) wen[i] = 4'(i) < w.nrows;
        wdat = row_in;
      end

      // ---- 5. preloads for the instruction entering execute, with the bypass
      if (w.pre != imap_pkg::PRE_NONE || w.row == imap_pkg::ROW_READ) begin
        if (wb && w.rd == wx.pre_ra && !`IMAP_MUT(5)) lo = res;
        if (wb && w.rd == wx.pre_rb && !`IMAP_MUT(5)) hi = res;
        xa = {{2{cw_pre[31]}}, cw_pre} + {18'h0, (w.pre_nohi ? 8'h00 : hi), lo};
        // the row: at the broadcast address (ld, vout, xst), at the per-PE
        // address (ldx), or the next rows of an xst
        mre = w.pre == imap_pkg::PRE_ROW || w.pre == imap_pkg::PRE_ADDR || w.row == imap_pkg::ROW_READ;
        if (w.pre == imap_pkg::PRE_ROW) mra = AI'(cw_pre[AW-1:0]);
        else if (w.pre == imap_pkg::PRE_ADDR) mra = AI'(xa[AW-1:0]);
        else mra = AI'(wx.addr[AW-1:0]);
`ifndef SYNTHESIS
        // the preloads see the registers as this edge leaves them (the
        // write-back bypass): ring source, per-PE address bytes
        pre_ok = 1'b1;
        if (w.pre == imap_pkg::PRE_RING || w.pre == imap_pkg::PRE_ADDR)
          pre_ok = lo == regs[wx.pre_ra[RW-1:0]];
        if (w.pre == imap_pkg::PRE_ADDR && !w.pre_nohi)
          pre_ok = pre_ok && hi == regs[wx.pre_rb[RW-1:0]];
        a_pe_preload :
        assert (pre_ok)
        else `IMAP_FAIL(a_pe_preload, pe_index);
`endif
        case (w.pre)
          imap_pkg::PRE_RING: ring_q <= lo;
          imap_pkg::PRE_ADDR: begin
            xaddr_q = xa[AW-1:0];
            xoff_q <= {(w.pre_nohi ? 8'h00 : hi), lo};
            oob = xa[33] || xa >= 34'(MEM_BYTES);
            st_q <= {oob, w.commit ? tn : st_q[ST], w.commit ? mn : st_q[SM]};
          end
          default: ;
        endcase
      end

      // ---- 6. the memory banks: this edge's row read and write
      if (mre || wen != 8'h00) begin
        if (mre) rlo_q <= mra[2:0];
        // the row's bytes in bank order: byte i goes to bank (wad + i) mod 8
        // (rotate left by wad mod 8 bytes; a shift by 8 / 64 gives 0)
        wenb = (wen << wad[2:0]) | (wen >> (4'd8 - {1'b0, wad[2:0]}));
        wdatb = (wdat << {wad[2:0], 3'b000}) | (wdat >> (7'd64 - {1'b0, wad[2:0], 3'b000}));
        `IMAP_PE_BANK(0, bank0)
        `IMAP_PE_BANK(1, bank1)
        `IMAP_PE_BANK(2, bank2)
        `IMAP_PE_BANK(3, bank3)
        `IMAP_PE_BANK(4, bank4)
        `IMAP_PE_BANK(5, bank5)
        `IMAP_PE_BANK(6, bank6)
        `IMAP_PE_BANK(7, bank7)
`ifndef SYNTHESIS
        // every byte written lies inside the memory (the CP faults a
        // transfer or an address past the end before any byte is written)
        for (int i = 0; i < 8; i++)
          if (wen[i])
            a_pe_mem_range :
            assert (32'(wad) + 32'(i) < 32'(MEM_BYTES))
            else `IMAP_FAIL(a_pe_mem_write, pe_index);
        if (mre) begin
          chk_q <= 1'b1;
          chk_ra <= mra;
        end
`endif
      end

      // reset (held by the CP for a few cycles)
      if (w.clr) begin
        for (int r = 0; r < NREGS; r++) regs[r] = 8'h00;
        c_q = 1'b0;
        mstk = '0;
        ring_q <= 8'h00;
        st_q <= 3'b001;
      end
    end
  end

endmodule

`undef IMAP_PE_BANK
