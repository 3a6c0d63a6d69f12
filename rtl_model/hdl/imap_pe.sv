`include "imap_mutants.svh"
`include "imap_assert.svh"
// One processing element (docs/isa.md 1.1, 4, 4.1): register file, 8-bit
// adder with carry, comparator and min/max, the shifter, the C / T / M flags,
// the mask stack, write-back gated by M, and the local memory
// (imap_pe_mem: one row read port, one row write port, both mappable to
// block RAMs; docs/rtl.md "The PE's local memory").
//
// The PE obeys the control word broadcast by the CP (imap_pkg::cw_t); it
// does nothing in a cycle without cw.act. Its outputs are registers (row_q:
// the memory's read registers and their write-first bypass). The cycle's
// work is one combinational block, registered by one clocked process.
// Operands are read in the last cycle of an instruction (commit) from the
// register file, which does not change while an instruction is in execute.
// Four things are read one edge earlier, at the edge where the next
// instruction enters execute (cw.pre): the ring source register (rxl /
// rxr), the per-PE address (ldx / stx) with the memory row at it (ldx), the
// memory row at the broadcast address (ld, vout, xst). ld and ldx take byte
// 0 of that row at commit, so the memory is read only at preload edges and
// at the row-read cycles of xst. Those preloads take what is written at
// that same edge from the bypasses: the register write-back's here, the
// memory's own in imap_pe_mem.
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

  localparam int AW = $clog2(MEM_BYTES > 1 ? MEM_BYTES : 2);
  localparam int RW = $clog2(NREGS > 1 ? NREGS : 2);
  localparam int SM = 0, ST = 1, SOOB = 2;  // bits of st_q

  logic [7:0] regs[NREGS] /*verilator public_flat_rw*/;
  logic c_q /*verilator public_flat_rd*/;
  logic [MASK_DEPTH-1:0] mstk /*verilator public_flat_rd*/;  // saved M values, top at bit 0
  logic [AW-1:0] xaddr_q;  // preloaded per-PE address
  logic [7:0] sh_acc;  // shifter: value being shifted
  logic [2:0] sh_rem;  // shifter: bits still to shift
  logic sh_c;  // shifter: last bit shifted out

  // The local memory: one row read port and one row write port
  // (imap_pe_mem). The read row is row_q: loaded at the preload edge of
  // ld / ldx (byte 0 is the operand), vout and xst, and at each ROW_READ
  // cycle of xst; held until the next read.
  logic m_re;
  logic [AW-1:0] m_ra, m_wa;
  logic [XROWS-1:0] m_we;
  logic [XROWS*8-1:0] m_wd;
  imap_pe_mem #(
      .BYTES(MEM_BYTES),
      .BANKS(XROWS)
  ) u_mem (
      .clk(clk),
      .pe_index(pe_index),
      .re(m_re),
      .ra(m_ra),
      .we(m_we),
      .wa(m_wa),
      .wd(m_wd),
      .rd(row_q)
  );

  // ---- This cycle's work (combinational; the clocked process below
  // registers it when cw.act).
  imap_pkg::cw_t w;
  imap_pkg::cwx_t wx;
  logic [7:0] a, b, res, lo, hi, mval, sh_acc_n;
  logic [8:0] sum;
  logic [2:0] s, sh_rem_n;
  logic sh_c_n, cn, tn, mn, act, wb, mwe, oob, rw, pre;
  logic [MASK_DEPTH-1:0] mstk_n;
  logic [AW-1:0] ma;
  logic [33:0] xa;
  always_comb begin
    w = cw;
    wx = cwx;
    act = st_q[SM];

    // ---- shifter pass (at most shift_bits bits)
    sh_acc_n = sh_acc;
    sh_rem_n = sh_rem;
    sh_c_n = sh_c;
    s = '0;
    if (w.first) begin
      sh_acc_n = regs[w.ra[RW-1:0]];
      sh_rem_n = w.bimm ? w.imm[2:0] : regs[w.rb[RW-1:0]][2:0];
      sh_c_n = c_q;
    end
    if (w.step && w.fn != imap_pkg::F_RING && sh_rem_n != 3'd0) begin
      s = (sh_rem_n < w.sbits) ? sh_rem_n : w.sbits;
      if (w.fn == imap_pkg::F_SHL) begin
        sh_c_n = sh_acc_n[3'(4'd8 - {1'b0, s})];
        sh_acc_n = sh_acc_n << s;
      end else begin
        sh_c_n = `IMAP_MUT(7) ? sh_acc_n[s] : sh_acc_n[s-3'd1];
        sh_acc_n = sh_acc_n >> s;
      end
      sh_rem_n = sh_rem_n - s;
    end

    // ---- execute (the commit cycle; mask commands: all PEs)
    a = regs[w.ra[RW-1:0]];
    b = w.bimm ? w.imm : regs[w.rb[RW-1:0]];
    res = a;
    sum = '0;
    cn = c_q;
    tn = st_q[ST];
    mn = st_q[SM];
    mstk_n = mstk;
    mwe = 1'b0;
    ma = wx.addr[AW-1:0];
    mval = regs[w.rd[RW-1:0]];
    wb = 1'b0;
    if (w.commit) begin
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
          res = sh_acc_n;
          cn = sh_c_n;
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
        // the byte preloaded at the edge where ld / ldx entered execute
        imap_pkg::F_LD, imap_pkg::F_LDX: res = row_q[7:0];
        imap_pkg::F_ST: mwe = act;
        imap_pkg::F_STX: begin
          mwe = act;
          ma = xaddr_q;
        end
        imap_pkg::F_RING: res = w.up ? nb_lo : nb_hi;
        default: ;
      endcase
      case (w.mask)
        imap_pkg::MK_IF: begin
          mn = st_q[SM] & st_q[ST];
          mstk_n = (mstk << 1) | MASK_DEPTH'(st_q[SM]);
        end
        imap_pkg::MK_ELSE: mn = (mstk[0] | `IMAP_MUT(11)) & ~st_q[SM];
        imap_pkg::MK_END: begin
          mn = mstk[0];
          mstk_n = mstk >> 1;
        end
        imap_pkg::MK_ALL: begin
          mn = 1'b1;
          mstk_n = '0;
        end
        default: ;
      endcase
      wb = (act || (`IMAP_MUT(2) && w.fn == imap_pkg::F_SUB)) && w.rd_we;
      if (!(act && w.t_we)) tn = st_q[ST];
    end

    // ---- row bus: rows written (vin on every PE, xld on the active PEs)
    rw = (w.row == imap_pkg::ROW_WRITE) && (!w.rowm || st_q[SM] || `IMAP_MUT(13));

    // ---- the memory's write port: the st / stx byte or the rows
    m_we = '0;
    m_wa = wx.addr[AW-1:0];
    m_wd = row_in;
    if (w.act && mwe) begin
      m_we = XROWS'(1);
      m_wa = ma;
      m_wd = {{(XROWS - 1) * 8{1'b0}}, mval};
    end else if (w.act && rw)
      for (int i = 0; i < XROWS; i++) m_we[i] = 4'(i) < w.nrows;

    // ---- preloads for the instruction entering execute, with the bypass
    // of this edge's write-back (the memory bypasses its own writes)
    pre = w.pre != imap_pkg::PRE_NONE || w.row == imap_pkg::ROW_READ;
    lo = regs[wx.pre_ra[RW-1:0]];
    hi = regs[wx.pre_rb[RW-1:0]];
    if (pre && wb && w.rd == wx.pre_ra && !`IMAP_MUT(5)) lo = res;
    if (pre && wb && w.rd == wx.pre_rb && !`IMAP_MUT(5)) hi = res;
    xa = {{2{cw_pre[31]}}, cw_pre} + {18'h0, (w.pre_nohi ? 8'h00 : hi), lo};
    oob = xa[33] || xa >= 34'(MEM_BYTES);
    m_re = w.act && (w.pre == imap_pkg::PRE_ROW || w.pre == imap_pkg::PRE_ADDR || w.row == imap_pkg::ROW_READ);
    m_ra = (w.pre == imap_pkg::PRE_ROW) ? cw_pre[AW-1:0] :
           (w.pre == imap_pkg::PRE_ADDR) ? xa[AW-1:0] : wx.addr[AW-1:0];
  end

`ifndef SYNTHESIS
  // a_pe_preload, register part: checked at the edge after a preload
  logic chk_lo, chk_hi;
  logic [RW-1:0] chk_ra, chk_rb;
  logic [7:0] pre_lo, pre_hi;
`endif

  always_ff @(posedge clk) begin
`ifndef SYNTHESIS
    // the preloaded ring source and per-PE address bytes equal the
    // registers as the preload edge left them (the write-back bypass)
    if (chk_lo)
      a_pe_preload :
      assert (pre_lo == regs[chk_ra] && (!chk_hi || pre_hi == regs[chk_rb]))
      else `IMAP_FAIL(a_pe_preload, pe_index);
    chk_lo <= w.act && (w.pre == imap_pkg::PRE_RING || w.pre == imap_pkg::PRE_ADDR);
    chk_hi <= w.act && w.pre == imap_pkg::PRE_ADDR && !w.pre_nohi;
    chk_ra <= wx.pre_ra[RW-1:0];
    chk_rb <= wx.pre_rb[RW-1:0];
    pre_lo <= lo;
    pre_hi <= hi;
`endif
    if (w.act) begin
      sh_acc <= sh_acc_n;
      sh_rem <= sh_rem_n;
      sh_c <= sh_c_n;
      if (w.step && w.fn == imap_pkg::F_RING) ring_q <= w.up ? nb_lo : nb_hi;

      if (w.commit) begin
        if (wb) regs[w.rd[RW-1:0]] <= res;
        if (act && w.c_we) c_q <= cn;
        mstk <= mstk_n;
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
          assert (!mn || mstk_n[0])
          else `IMAP_FAIL(a_pe_mask_nest, pe_index);
`endif
      end
`ifndef SYNTHESIS
      // xld writes its rows on the active PEs only
      a_pe_masked_row :
      assert (!(rw && w.rowm) || st_q[SM])
      else `IMAP_FAIL(a_pe_masked_row, pe_index);
      // one write source per edge: a st / stx byte or the rows of the
      // instruction in execute, never both (the memory has one write port)
      a_pe_mem_write :
      assert (!(mwe && rw))
      else `IMAP_FAIL(a_pe_mem_write, pe_index);
`endif

      case (w.pre)
        imap_pkg::PRE_RING: ring_q <= lo;
        imap_pkg::PRE_ADDR: begin
          xaddr_q <= xa[AW-1:0];
          xoff_q <= {(w.pre_nohi ? 8'h00 : hi), lo};
          st_q <= {oob, w.commit ? tn : st_q[ST], w.commit ? mn : st_q[SM]};
        end
        default: ;
      endcase

      // reset (held by the CP for a few cycles)
      if (w.clr) begin
        for (int r = 0; r < NREGS; r++) regs[r] <= 8'h00;
        c_q <= 1'b0;
        mstk <= '0;
        ring_q <= 8'h00;
        st_q <= 3'b001;
      end
    end
  end

endmodule
