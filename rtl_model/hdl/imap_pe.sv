`include "imap_mutants.svh"
`include "imap_assert.svh"
// One processing element (docs/isa.md 1.1, 4, 4.1): register file, 8-bit
// adder with carry, comparator and min/max, the shifter, the C / T / M flags,
// the mask stack, write-back gated by M, and the local memory with its port
// (broadcast address, per-PE address for ldx / stx, and the row port of the
// video line and external-memory transfer buses).
//
// The PE obeys the control word broadcast by the CP (imap_pkg::cw_t); it
// does nothing in a cycle without cw.act. Every output is a register, so a
// cycle of the whole array is one clocked process per PE. Operands are read
// in the last cycle of an instruction (commit) from the register file,
// which does not change while an instruction is in execute. Three things are
// read one edge earlier, at the edge where the next instruction enters
// execute (cw.pre): the ring source register (rxl / rxr), the per-PE
// address (ldx / stx), and the first memory row of vout / xst. Those
// preloads take what is written at that same edge from the write-back
// bypass.
//
// Coding rule: every read of the register file and of the local memory
// comes before any write in the process (the writes are blocking: nothing
// outside this process reads them), so the bypass is explicit.
`include "imap_ports.svh"
module imap_pe
#(
    parameter int NREGS = 16,
    parameter int MEM_BYTES = 1024,
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

  logic [7:0] regs[NREGS] /*verilator public_flat_rw*/;
  logic [7:0] mem[MEM_BYTES] /*verilator public_flat_rw*/;
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
  logic [AW-1:0] ma, pa, d;
  logic [33:0] xa;
  logic [XROWS*8-1:0] prow;
`ifndef SYNTHESIS
  logic pre_ok;  // a_pe_preload
`endif

  always_ff @(posedge clk) begin

    // Every temporary is set before the activity test (lets the simulator
    // keep them in machine registers).
    w = cw;
    wx = cwx;
    {a, b, res, lo, hi, mval} = '0;
    sum = '0;
    {cn, tn, mn, act, wb, mwe, oob, rw} = '0;
    s = '0;
    {ma, pa, d} = '0;
    xa = '0;
    prow = '0;
    if (w.act) begin
      act = st_q[SM];

      // ---- 1. preload reads (before any write of this edge)
      if (w.pre != imap_pkg::PRE_NONE || w.row == imap_pkg::ROW_READ) begin
        lo = regs[wx.pre_ra[RW-1:0]];
        hi = regs[wx.pre_rb[RW-1:0]];
        pa = (w.pre == imap_pkg::PRE_ROW) ? cw_pre[AW-1:0] : wx.addr[AW-1:0];
        for (int i = 0; i < XROWS; i++) prow[i*8+:8] = mem[pa+AW'(i)];
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
          imap_pkg::F_LD: res = mem[wx.addr[AW-1:0]];
          imap_pkg::F_LDX: res = mem[xaddr_q];
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
        if (mwe) mem[ma] = mval;
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
      if (rw)
        for (int i = 0; i < XROWS; i++)
          if (4'(i) < w.nrows) begin
            mem[wx.addr[AW-1:0]+AW'(i)] = row_in[i*8+:8];
          end

      // ---- 5. preloads for the instruction entering execute, with the bypass
      if (w.pre != imap_pkg::PRE_NONE || w.row == imap_pkg::ROW_READ) begin
        if (wb && w.rd == wx.pre_ra && !`IMAP_MUT(5)) lo = res;
        if (wb && w.rd == wx.pre_rb && !`IMAP_MUT(5)) hi = res;
        for (int i = 0; i < XROWS; i++) begin
          d = (pa + AW'(i)) - wx.addr[AW-1:0];  // row of this edge's row writes
          if (mwe && ma == pa + AW'(i)) prow[i*8+:8] = mval;
          else if (rw && d < AW'(w.nrows)) prow[i*8+:8] = row_in[d*8+:8];
        end
        row_q <= prow;
`ifndef SYNTHESIS
        // the preloads see the registers and the memory as this edge leaves
        // them (the write-back bypass): ring source, per-PE address bytes,
        // the rows of vout / xst
        pre_ok = 1'b1;
        if (w.pre == imap_pkg::PRE_RING || w.pre == imap_pkg::PRE_ADDR)
          pre_ok = lo == regs[wx.pre_ra[RW-1:0]];
        if (w.pre == imap_pkg::PRE_ADDR && !w.pre_nohi)
          pre_ok = pre_ok && hi == regs[wx.pre_rb[RW-1:0]];
        for (int i = 0; i < XROWS; i++) pre_ok = pre_ok && prow[i*8+:8] == mem[pa+AW'(i)];
        a_pe_preload :
        assert (pre_ok)
        else `IMAP_FAIL(a_pe_preload, pe_index);
`endif
        case (w.pre)
          imap_pkg::PRE_RING: ring_q <= lo;
          imap_pkg::PRE_ADDR: begin
            xa = {{2{cw_pre[31]}}, cw_pre} + {18'h0, (w.pre_nohi ? 8'h00 : hi), lo};
            xaddr_q = xa[AW-1:0];
            xoff_q <= {(w.pre_nohi ? 8'h00 : hi), lo};
            oob = xa[33] || xa >= 34'(MEM_BYTES);
            st_q <= {oob, w.commit ? tn : st_q[ST], w.commit ? mn : st_q[SM]};
          end
          default: ;
        endcase
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
