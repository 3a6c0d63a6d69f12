`include "imap_mutants.svh"
`include "imap_assert.svh"
// The control processor (docs/isa.md 1.2, 3, 4): a three-stage pipeline
//
//   F  fetch      instruction memory read (registered), PC sequencing, the
//                 redirect of taken branches (resolved in D)
//   D  decode     format check, CP register read with forwarding from X,
//                 branch decision and target, broadcast address and byte,
//                 the static fault checks (address ranges)
//   X  execute    one instruction at a time for exactly its cost in cycles:
//                 the sequencer counts the cost-table cycles of its class
//                 (the cost table is a set of strap inputs, so any setting
//                 runs without rebuilding), drives the control word to the
//                 PEs, steps the shifter passes and the ring hops, runs the
//                 external-memory transfer engine (a byte counter against
//                 the shared path's bytes per cycle), and commits the CP
//                 side (CP registers, param block, return stack, mask-stack
//                 depth, halt) in the instruction's last cycle.
//
// The machine cycle counter (mcycle) counts every clock in which X holds an
// instruction or a taken-branch refill bubble. A zero-cost instruction
// (phase, or xld / xst of 0 bytes with xfer_setup = 0) holds X for one clock
// that is not a machine cycle; so do the two clocks that fill the pipeline
// after reset (docs/rtl.md, "Clocks and machine cycles").
`include "imap_ports.svh"
module imap_cp
#(
`include "imap_params.svh"
) (
    `IMAP_CLOCK_PORTS
    input imap_pkg::host_t host,  // program and param block (written while rst_n = 0)
    input imap_pkg::straps_t straps,  // the cost table and the machine configuration
    // control word to the array
    output imap_pkg::cw_t cw,
    output imap_pkg::cwx_t cwx,
    output logic [31:0] cw_pre,
    // mask bus
    output logic red_status,
    output logic red_memx,
    output logic red_count,
    input logic any_t,
    input logic all_t,
    input logic memx_bad,
    input logic [15:0] memx_pe,
    input logic [15:0] memx_off,  // its per-PE offset (rb:ra), for the fault report
    input logic [16:0] active_n,
    // external-memory transfer engine and video unit (the board, outside the chip)
    output logic xe_pf,  // prefetch ext rows [xe_prow, +XROWS) onto the row bus
    output logic [31:0] xe_prow,
    output logic xe_wr,  // write xe_n ext rows from the PEs' row ports
    output logic [31:0] xe_wrow,
    output logic [3:0] xe_n,
    output logic vid_open,  // vin / vout enters execute: check (and fetch) the line
    output logic vid_out,  // ... 1 = vout
    output logic [0:0] vid_oport,
    output logic [31:0] vid_oy,
    output logic [31:0] vid_ox,
    output logic vid_put,  // vout commits: send the PEs' row to the output line
    output logic [0:0] vid_pport,
    output logic [31:0] vid_py,
    output logic [31:0] vid_px,
    input logic [1:0] vid_status,  // of the last vid_open: 0 ok, 1 no port, 2 bad line
    input logic [63:0] vid_ready,  // ... vin: the cycle its pixels have arrived (camera)
    // status
    // performance-counter events (imap_perf)
    output logic ev_cycle,  // this clock is a machine cycle
    output imap_pkg::kind_t ev_kind,  // ... of this kind (refill bubbles: K_CP)
    output logic [15:0] ev_phase,  // ... charged to this phase
    output logic ev_pe,  // ... of a PE instruction (ALU, shifter, memory, ring)
    output logic [16:0] ev_active,  // PEs with M = 1
    output logic ev_retire,  // an instruction retires
    output logic [7:0] ev_op,  // ... with this opcode
    // status
    output logic halted  /*verilator public_flat_rd*/,
    output logic faulted  /*verilator public_flat_rd*/,
    output logic [63:0] mcycle  /*verilator public_flat_rd*/
);


  localparam int AW = $clog2(MEM_BYTES > 1 ? MEM_BYTES : 2);
  localparam int PCW = 24;

  // ===========================================================================
  // State
  // ===========================================================================
  logic [63:0] imem[IMEM_WORDS];
  logic [31:0] param[256] /*verilator public_flat_rd*/;
  logic [31:0] creg[16] /*verilator public_flat_rd*/;
  logic [PCW-1:0] cstk[CALL_DEPTH];
  logic [8:0] csp /*verilator public_flat_rd*/;  // return stack depth
  logic [8:0] msp /*verilator public_flat_rd*/;  // mask stack depth (the same on every PE)
  logic [15:0] phase_q /*verilator public_flat_rd*/;
  logic [63:0] instret /*verilator public_flat_rd*/;
  logic run_q;  // out of reset, not stopped
  logic [1:0] clr_q;  // PE clear during reset

  // F / D
  logic [PCW:0] f_pc;  // next PC to fetch (one bit wider: past the end)
  logic d_v;
  logic [PCW:0] d_pc;
  logic [63:0] d_ir;

  // X
  logic x_v, x_first, x_zero;
  logic [PCW:0] x_pc /*verilator public_flat_rd*/;
  logic [63:0] x_ir;
  logic [7:0] x_op;
  imap_pkg::kind_t x_kind;
  imap_pkg::fault_t x_dflt;  // fault found in decode
  logic [63:0] x_faddr;  // its address
  logic [31:0] x_a, x_b;  // CP operand values (forwarded in D)
  logic [31:0] x_addr;  // broadcast address / local base
  logic x_taken;  // taken branch
  logic [31:0] x_cnt;  // remaining cycles of the current sequencer step
  logic [63:0] x_cyc0;  // machine cycle at issue
  imap_pkg::cw_t x_cw;  // static part of the control word
  logic [31:0] bub;  // refill bubbles still to come
  // shifter passes
  logic [2:0] x_shrem;
  logic x_shpass;  // in the pass cycles
  // ring
  logic [16:0] x_hops;
  logic [31:0] x_hcyc;
  // transfer engine
  logic x_setup;  // in the setup cycles
  logic [31:0] x_beat;  // cycles left before the current beat moves its bytes (c_ext_beat)
  logic [47:0] x_brem;  // bytes still to cross the path
  logic [16:0] x_act;  // active PEs of the transfer (their bytes cross the path)
  logic [31:0] x_cred;  // bytes of the row being filled
  logic [31:0] x_rdone;  // rows transferred
  logic [31:0] x_ebase;  // external address
  logic [31:0] x_len;  // rows (bytes per PE)
  logic x_xst;
  // video
  logic [0:0] x_vport;
  logic [31:0] x_vy, x_vx;
  // the active-PE count (perf)
  logic [16:0] m_active;
  logic m_dirty;
  // PEs with M = 1 now: the array's count while a mask change is pending
  logic [16:0] active_now;
  assign active_now = m_dirty ? active_n : m_active;
  // fault record
  imap_pkg::fault_t f_code /*verilator public_flat_rd*/;
  logic [PCW:0] f_pc_q /*verilator public_flat_rd*/;
  logic [63:0] f_cyc /*verilator public_flat_rd*/;
  logic [31:0] f_pe /*verilator public_flat_rd*/;
  logic [63:0] f_addr /*verilator public_flat_rd*/;


  // ===========================================================================
  // Decode (D): combinational
  // ===========================================================================
  logic [7:0] d_op, d_rd, d_ra, d_rb;
  logic [31:0] d_imm;
  imap_pkg::fmt_t d_fmt;
  imap_pkg::kind_t d_kind;
  logic d_illegal;

  // temporaries of the processes below
  logic regs_ok;
  logic [31:0] ret_top, xc, xnr, x_imm;
  logic [PCW:0] fa;

  // X's pending CP register write, forwarded to D
  logic x_cwe;
  logic [3:0] x_cidx;
  logic [31:0] x_cres;

  function automatic logic [31:0] rdc(input logic [3:0] i, input logic fwe,
                                      input logic [3:0] fidx, input logic [31:0] fval,
                                      input logic [31:0] rf);
    rdc = (fwe && fidx == i) ? fval : rf;
  endfunction

  logic [31:0] d_ca, d_cb, d_cd, d_cn, d_cy, d_cx, d_base;
  logic [33:0] d_addr;  // cB + off, signed 34 bit
  logic [33:0] d_xend;  // local end of a transfer
  logic [33:0] d_eend;  // external end of a transfer
  logic d_taken;
  logic [PCW:0] d_target;
  imap_pkg::fault_t d_flt;
  logic [63:0] d_faddr;
  logic [7:0] d_byte;  // broadcast byte (lc / lcb)
  logic [31:0] d_ldxoff;

  always_comb begin
    d_op = d_ir[7:0];
    d_rd = d_ir[15:8];
    d_ra = d_ir[23:16];
    d_rb = d_ir[31:24];
    d_imm = d_ir[63:32];
    d_fmt = imap_pkg::op_format(d_op);
    d_kind = imap_pkg::op_kind(d_op);

    // ---- format check: fields an instruction does not use are 0, registers
    // exist, immediates in range (docs/isa.md 3)
    regs_ok = 1'b1;
    d_illegal = 1'b0;
    case (d_fmt)
      imap_pkg::FMT_NONE: d_illegal = d_rd != 0 || d_ra != 0 || d_rb != 0 || d_imm != 0;
      imap_pkg::FMT_RRR:
      d_illegal = d_imm != 0 || d_rd >= straps.cfg_pe_regs || d_ra >= straps.cfg_pe_regs || d_rb >= straps.cfg_pe_regs;
      imap_pkg::FMT_RRI8: d_illegal = d_rb != 0 || d_imm > 255 || d_rd >= straps.cfg_pe_regs || d_ra >= straps.cfg_pe_regs;
      imap_pkg::FMT_RR: d_illegal = d_rb != 0 || d_imm != 0 || d_rd >= straps.cfg_pe_regs || d_ra >= straps.cfg_pe_regs;
      imap_pkg::FMT_RI8: d_illegal = d_ra != 0 || d_rb != 0 || d_imm > 255 || d_rd >= straps.cfg_pe_regs;
      imap_pkg::FMT_RSH: d_illegal = d_rb != 0 || d_imm > 7 || d_rd >= straps.cfg_pe_regs || d_ra >= straps.cfg_pe_regs;
      imap_pkg::FMT_CMP: d_illegal = d_rd != 0 || d_imm != 0 || d_ra >= straps.cfg_pe_regs || d_rb >= straps.cfg_pe_regs;
      imap_pkg::FMT_CMPI: d_illegal = d_rd != 0 || d_rb != 0 || d_imm > 255 || d_ra >= straps.cfg_pe_regs;
      imap_pkg::FMT_R: d_illegal = d_ra != 0 || d_rb != 0 || d_imm != 0 || d_rd >= straps.cfg_pe_regs;
      imap_pkg::FMT_RC: d_illegal = d_rb != 0 || d_imm != 0 || d_ra > 15 || d_rd >= straps.cfg_pe_regs;
      imap_pkg::FMT_RCK: d_illegal = d_rb != 0 || d_imm > 3 || d_ra > 15 || d_rd >= straps.cfg_pe_regs;
      imap_pkg::FMT_RK: d_illegal = d_ra != 0 || d_rb != 0 || d_imm > 3 || d_rd >= straps.cfg_pe_regs;
      imap_pkg::FMT_LD: d_illegal = d_ra != 0 || (d_rb > 15 && d_rb != 128) || d_rd >= straps.cfg_pe_regs;
      imap_pkg::FMT_LDX:
      d_illegal = !straps.cfg_indirect || d_imm[31:30] != 0 || d_rd >= straps.cfg_pe_regs ||
          d_ra >= straps.cfg_pe_regs || d_rb >= straps.cfg_pe_regs || (d_imm[29] && d_rb != 0) ||
          (!d_imm[28] && d_imm[27:24] != 0);
      imap_pkg::FMT_XFER: d_illegal = d_rd > 15 || d_ra > 15 || (d_rb > 15 && d_rb != 128);
      imap_pkg::FMT_RING:
      d_illegal = d_rb != 0 || d_imm == 0 || d_imm > 65535 || d_rd >= straps.cfg_pe_regs ||
          d_ra >= straps.cfg_pe_regs;
      imap_pkg::FMT_STAT: d_illegal = d_ra != 0 || d_rb != 0 || d_imm != 0 || d_rd > 15;
      imap_pkg::FMT_CI: d_illegal = d_ra != 0 || d_rb != 0 || d_rd > 15;
      imap_pkg::FMT_CC: d_illegal = d_rb != 0 || d_imm != 0 || d_rd > 15 || d_ra > 15;
      imap_pkg::FMT_CCC: d_illegal = d_imm != 0 || d_rd > 15 || d_ra > 15 || d_rb > 15;
      imap_pkg::FMT_CCI: d_illegal = d_rb != 0 || d_rd > 15 || d_ra > 15;
      imap_pkg::FMT_CSH: d_illegal = d_rb != 0 || d_imm > 31 || d_rd > 15 || d_ra > 15;
      imap_pkg::FMT_CMEM: d_illegal = d_ra != 0 || d_rd > 15 || (d_rb > 15 && d_rb != 128);
      imap_pkg::FMT_J: d_illegal = d_rd != 0 || d_ra != 0 || d_rb != 0 || d_imm >= straps.cfg_prog_len;
      imap_pkg::FMT_BCC: d_illegal = d_rd != 0 || d_ra > 15 || d_rb > 15 || d_imm >= straps.cfg_prog_len;
      imap_pkg::FMT_B1: d_illegal = d_rd != 0 || d_rb != 0 || d_ra > 15 || d_imm >= straps.cfg_prog_len;
      imap_pkg::FMT_VIDEO: d_illegal = d_rd > 1 || (d_rb > 15 && d_rb != 128);
      imap_pkg::FMT_PHASE: d_illegal = d_rd != 0 || d_ra != 0 || d_rb != 0 || d_imm > 65535;
      default: d_illegal = 1'b1;
    endcase

    // ---- CP register reads, forwarded from the instruction in X
    d_ca = rdc(d_ra[3:0], x_cwe, x_cidx, x_cres, creg[d_ra[3:0]]);
    d_cb = rdc(d_rb[3:0], x_cwe, x_cidx, x_cres, creg[d_rb[3:0]]);
    d_cd = rdc(d_rd[3:0], x_cwe, x_cidx, x_cres, creg[d_rd[3:0]]);
    d_cn = rdc(d_imm[27:24], x_cwe, x_cidx, x_cres, creg[d_imm[27:24]]);
    d_cy = rdc(d_ra[3:0], x_cwe, x_cidx, x_cres, creg[d_ra[3:0]]);
    d_cx = rdc(d_ra[7:4], x_cwe, x_cidx, x_cres, creg[d_ra[7:4]]);
    d_base = (d_rb == 8'd128) ? 32'h0 :
             (`IMAP_MUT(6) && (d_op == imap_pkg::OP_LD || d_op == imap_pkg::OP_ST)) ? creg[d_rb[3:0]] : d_cb;
    d_addr = {{2{d_base[31]}}, d_base} + {{2{d_imm[31]}}, d_imm};
    d_xend = d_addr + {{2{d_cd[31]}}, d_cd};
    d_eend = {2'b00, d_ca} + {{2{d_cd[31]}}, d_cd};
    d_ldxoff = {{8{d_imm[23]}}, d_imm[23:0]} + (d_imm[28] ? d_cn : 32'h0);
    d_byte = (d_op == imap_pkg::OP_LCB) ? d_ca[d_imm[1:0]*8+:8] : d_ca[7:0];

    // ---- branches (resolved here; the fetch is redirected when the branch
    // enters X)
    if (x_v && x_op == imap_pkg::OP_CALL) ret_top = 32'(x_pc) + 32'd1;
    else if (x_v && x_op == imap_pkg::OP_RET) ret_top = (csp >= 9'd2) ? 32'(cstk[csp-2]) : 32'h0;
    else ret_top = (csp >= 9'd1) ? 32'(cstk[csp-1]) : 32'h0;
    d_target = (d_op == imap_pkg::OP_RET) ? ret_top[PCW:0] : d_imm[PCW:0];
    case (d_op)
      imap_pkg::OP_JMP, imap_pkg::OP_CALL, imap_pkg::OP_RET: d_taken = 1'b1;
      imap_pkg::OP_BEQ: d_taken = d_ca == d_cb;
      imap_pkg::OP_BNE: d_taken = d_ca != d_cb;
      imap_pkg::OP_BLT: d_taken = $signed(d_ca) < $signed(d_cb);
      imap_pkg::OP_BGE: d_taken = $signed(d_ca) >= $signed(d_cb);
      imap_pkg::OP_BZ: d_taken = d_ca == 32'h0;
      imap_pkg::OP_BNZ: d_taken = d_ca != 32'h0;
      imap_pkg::OP_LOOP: d_taken = d_ca != 32'h1;  // cA - 1 != 0
      default: d_taken = 1'b0;
    endcase

    // ---- faults found in decode (range checks on forwarded values)
    d_flt = imap_pkg::FLT_NONE;
    d_faddr = 64'h0;
    if (32'(d_pc) >= straps.cfg_prog_len) begin
      d_flt = imap_pkg::FLT_PC_END;
      d_faddr = 64'(d_pc);
    end else if (d_illegal) begin
      d_flt = imap_pkg::FLT_ILLEGAL;
    end else begin
      case (d_op)
        imap_pkg::OP_LD, imap_pkg::OP_ST:
        if (d_addr[33] || d_addr >= 34'(MEM_BYTES)) begin
          d_flt = imap_pkg::FLT_MEM;
          d_faddr = {{30{d_addr[33]}}, d_addr};
        end
        imap_pkg::OP_CLD, imap_pkg::OP_CST:
        if (d_addr[33] || d_addr >= 34'd256) begin
          d_flt = imap_pkg::FLT_PARAM;
          d_faddr = {{30{d_addr[33]}}, d_addr};
        end
        imap_pkg::OP_VIN, imap_pkg::OP_VOUT:
        if (d_addr[33] || d_addr >= 34'(MEM_BYTES)) begin
          d_flt = imap_pkg::FLT_VID_MEM;
          d_faddr = {{30{d_addr[33]}}, d_addr};
        end
        imap_pkg::OP_XLD, imap_pkg::OP_XST:
        if (!straps.cfg_ext_on) d_flt = imap_pkg::FLT_EXT_NONE;
        else if (d_cd[31]) begin
          d_flt = imap_pkg::FLT_XFER_LEN;
          d_faddr = {{32{d_cd[31]}}, d_cd};
        end else if (d_addr[33] || d_xend > 34'(MEM_BYTES)) begin
          // reported: the last byte of the range (the instruction-set model's choice)
          d_flt = imap_pkg::FLT_XFER_LOCAL;
          d_faddr = {{30{d_xend[33]}}, d_xend} - 64'd1;
        end else if (d_ca[31] || d_eend > 34'(EXT_BYTES)) begin
          d_flt = imap_pkg::FLT_XFER_EXT;
          d_faddr = {{30{d_eend[33]}}, d_eend} - 64'd1;
        end
        default: ;
      endcase
    end
  end

  // ===========================================================================
  // Execute (X): the sequencer's view of the current cycle
  // ===========================================================================
  logic x_last;  // last cycle of the instruction in X
  logic x_step;  // shifter pass / ring hop in this cycle
  logic [31:0] x_rows;  // transfer: rows completed by the end of this cycle
  logic [31:0] x_credn;  // transfer: row credit after this cycle
  logic [16:0] xa_now;  // transfer: active PEs (counted in its first cycle)
  logic [47:0] xb_now;  // transfer: bytes still to cross at the start of this cycle
  logic x_zn;  // a zero-cost instruction (phase; xld / xst moving nothing without setup)
  logic x_vwait;  // vin waiting for the camera: its pixels arrive at vid_ready
  imap_pkg::fault_t x_flt;  // fault raised in this cycle (first cycle only)
  logic [31:0] x_fpe;
  logic [63:0] x_fad;
  logic x_commit;
  logic x_free;  // X can take the instruction in D at the end of this cycle
  logic d_adv;  // ... and it does
  logic count_now;  // this clock is a machine cycle
  logic x_bubble;  // a taken branch: refill bubbles follow
  logic [8:0] msp_next, csp_next;  // stack depths after the instruction in X
  logic [2:0] sb;

  always_comb begin
    sb = (straps.c_shift_bits[2:0] == 3'd0) ? 3'd1 : straps.c_shift_bits[2:0];
    x_step = 1'b0;
    x_last = 1'b0;
    x_rows = x_rdone;
    x_credn = x_cred;
    // the transfer counts the active PEs in its first cycle (a mask command
    // just before it has its count on the mask bus now: red_count)
    xa_now = x_first ? (`IMAP_MUT(14) ? 17'(P) : active_now) : x_act;
    xb_now = x_first ? 48'(x_len) * 48'(xa_now) : x_brem;
    x_zn = x_zero || (x_kind == imap_pkg::K_XFER && !x_setup && xb_now == 48'd0);
    x_vwait = x_v && x_op == imap_pkg::OP_VIN && mcycle < vid_ready;
    xc = 32'h0;
    xnr = 32'h0;
    case (x_kind)
      imap_pkg::K_SHIFT: begin
        // (alu - 1) cycles of ALU latency, then passes of sb bits
        x_step = x_shpass || x_cnt == 32'd0;
        x_last = x_step && (x_shrem <= sb);
      end
      imap_pkg::K_RING: begin
        x_step = (x_hcyc == 32'd1);
        x_last = x_step && (x_hops == 17'd1);
      end
      imap_pkg::K_XFER: begin
        if (x_zn) x_last = 1'b1;
        else if (x_setup) x_last = (x_cnt == 32'd0) && (xb_now == 48'd0);
        else if (x_beat != 32'd0) x_last = 1'b0;  // the path is busy: bytes move at the beat's end
        else begin
          // data cycle: c_ext_bpc bytes cross the path; a row is complete
          // when the bytes of all active PEs have crossed
          xc = x_cred + straps.c_ext_bpc;
          xnr = 32'd0;
          for (int i = 0; i < XROWS; i++)
            if (xc >= 32'(xa_now)) begin
              xc = xc - 32'(xa_now);
              xnr = xnr + 32'd1;
            end
          x_credn = xc;
          x_last = (xb_now <= 48'(straps.c_ext_bpc));
          x_rows = x_last ? x_len : x_rdone + xnr;
          if (x_last && x_len != 32'd0 && ((`IMAP_MUT(4) && !x_xst) || (`IMAP_MUT(12) && x_xst)))
            x_rows = x_len - 32'd1;
        end
      end
      default: x_last = (x_cnt == 32'd0) && !x_vwait;
    endcase

    // faults, checked in the first cycle (precise: nothing is committed)
    x_flt = imap_pkg::FLT_NONE;
    x_fpe = 32'hFFFF_FFFF;
    x_fad = x_faddr;
    if (x_v && x_first) begin
      if (mcycle >= straps.cfg_watchdog) x_flt = imap_pkg::FLT_WATCHDOG;  // the run would be longer
      else if (x_dflt != imap_pkg::FLT_NONE) x_flt = x_dflt;
      else
        case (x_op)
          imap_pkg::OP_MIF:
          if ({1'b0, msp} >= {1'b0, straps.cfg_mask_depth} + {9'd0, `IMAP_MUT(9)})
            x_flt = imap_pkg::FLT_MASK_OVF;
          imap_pkg::OP_MELSE, imap_pkg::OP_MEND: if (msp == 9'd0) x_flt = imap_pkg::FLT_MASK_UNF;
          imap_pkg::OP_CALL: if (csp >= straps.cfg_call_depth) x_flt = imap_pkg::FLT_CALL_OVF;
          imap_pkg::OP_RET: if (csp == 9'd0) x_flt = imap_pkg::FLT_CALL_UNF;
          imap_pkg::OP_LDX, imap_pkg::OP_STX:
          if (memx_bad) begin
            x_flt = imap_pkg::FLT_MEMX;
            x_fpe = 32'(memx_pe);
            x_fad = x_faddr + 64'(memx_off);  // base (cN + off) + the PE's offset
          end
          imap_pkg::OP_VIN, imap_pkg::OP_VOUT:
          if (vid_status == 2'd1) x_flt = imap_pkg::FLT_VID_PORT;
          else if (vid_status == 2'd2) x_flt = imap_pkg::FLT_VID_LINE;
          default: ;
        endcase
    end
    x_commit = x_v && x_last && x_flt == imap_pkg::FLT_NONE && run_q;

    x_bubble = x_taken && !(`IMAP_MUT(10) && x_op == imap_pkg::OP_LOOP);
    if (!run_q) x_free = 1'b0;
    else if (x_v) x_free = x_commit && !(x_bubble && straps.c_branch_taken != 0) && x_op != imap_pkg::OP_HALT;
    else if (bub != 32'd0) x_free = (bub == 32'd1);
    else x_free = 1'b1;
    d_adv = d_v && x_free;
    count_now = run_q && ((x_v && !x_zn && !(x_first && x_flt != imap_pkg::FLT_NONE)) || bub != 32'd0);
    case (x_op)
      imap_pkg::OP_MIF: msp_next = msp + 9'd1;
      imap_pkg::OP_MEND: msp_next = msp - 9'd1;
      imap_pkg::OP_MALL: msp_next = 9'd0;
      default: msp_next = msp;
    endcase
    case (x_op)
      imap_pkg::OP_CALL: csp_next = csp + 9'd1;
      imap_pkg::OP_RET: csp_next = csp - 9'd1;
      default: csp_next = csp;
    endcase
  end

  // CP result of the instruction in X (committed at its last cycle, forwarded
  // to D before that): a row per CP-register-writing opcode, {write, value}
  always_comb begin
    x_imm = x_ir[63:32];
    x_cwe = 1'b0;
    x_cidx = x_ir[11:8];
    x_cres = 32'h0;
    if (x_v)
      case (x_op)
        imap_pkg::OP_CLI: begin x_cwe = 1'b1; x_cres = x_imm; end
        imap_pkg::OP_CMOV: begin x_cwe = 1'b1; x_cres = x_a; end
        imap_pkg::OP_CADD: begin x_cwe = 1'b1; x_cres = x_a + x_b; end
        imap_pkg::OP_CADDI: begin x_cwe = 1'b1; x_cres = x_a + x_imm; end
        imap_pkg::OP_CSUB: begin x_cwe = 1'b1; x_cres = x_a - x_b; end
        imap_pkg::OP_CSUBI: begin x_cwe = 1'b1; x_cres = x_a - x_imm; end
        imap_pkg::OP_CAND: begin x_cwe = 1'b1; x_cres = x_a & x_b; end
        imap_pkg::OP_CANDI: begin x_cwe = 1'b1; x_cres = x_a & x_imm; end
        imap_pkg::OP_COR: begin x_cwe = 1'b1; x_cres = x_a | x_b; end
        imap_pkg::OP_CORI: begin x_cwe = 1'b1; x_cres = x_a | x_imm; end
        imap_pkg::OP_CXOR: begin x_cwe = 1'b1; x_cres = x_a ^ x_b; end
        imap_pkg::OP_CXORI: begin x_cwe = 1'b1; x_cres = x_a ^ x_imm; end
        imap_pkg::OP_CSHLI: begin x_cwe = 1'b1; x_cres = x_a << x_imm[4:0]; end
        imap_pkg::OP_CSHRI: begin x_cwe = 1'b1; x_cres = x_a >> x_imm[4:0]; end
        imap_pkg::OP_CSRAI: begin x_cwe = 1'b1; x_cres = $unsigned($signed(x_a) >>> x_imm[4:0]); end
        imap_pkg::OP_CLD: begin x_cwe = 1'b1; x_cres = param[x_addr[7:0]]; end
        imap_pkg::OP_LOOP: begin x_cwe = 1'b1; x_cidx = x_ir[19:16]; x_cres = x_a - 32'd1; end
        imap_pkg::OP_RANY: begin x_cwe = 1'b1; x_cres = {31'h0, any_t}; end
        imap_pkg::OP_RALL: begin x_cwe = 1'b1; x_cres = {31'h0, all_t}; end
        default: ;
      endcase
  end

  // ===========================================================================
  // The control word and the unit strobes (combinational)
  // ===========================================================================
  always_comb begin
    cw = x_cw;
    cw.clr = clr_q != 2'd0;
    cw.trace = straps.cfg_trace;
    cw.commit = x_commit;
    cw.first = x_v && x_first && x_kind == imap_pkg::K_SHIFT;  // shifter load
    cw.step = x_v && x_step;
    cw.sbits = sb;
    cw.row = imap_pkg::ROW_NONE;
    cw.nrows = 4'd0;
    cw.rowm = 1'b0;
    cw.pre = imap_pkg::PRE_NONE;
    cw.pre_nohi = d_imm[29];
    cwx.pre_ra = d_ra[5:0];
    cwx.pre_rb = d_rb[5:0];
    cwx.addr = x_addr[19:0];
    cw_pre = d_addr[31:0];
    xe_pf = 1'b0;
    xe_prow = d_ca;
    xe_wr = 1'b0;
    xe_wrow = x_ebase + x_rdone;
    xe_n = 4'(x_rows - x_rdone);
    vid_open = 1'b0;
    vid_out = (d_op == imap_pkg::OP_VOUT);
    vid_oport = d_rd[0];
    vid_oy = d_cy;
    vid_ox = d_cx;
    vid_put = 1'b0;
    vid_pport = x_vport;
    vid_py = x_vy;
    vid_px = x_vx;

    // this cycle's row operations
    if (x_v && run_q && !(x_first && x_flt != imap_pkg::FLT_NONE)) begin
      if (x_op == imap_pkg::OP_VIN && x_commit) begin
        cw.row = imap_pkg::ROW_WRITE;
        cw.nrows = 4'd1;
      end
      if (x_op == imap_pkg::OP_VOUT && x_commit) vid_put = 1'b1;
      if (x_kind == imap_pkg::K_XFER && !x_zn && !x_setup) begin
        if (!x_xst) begin
          cw.row = (x_rows != x_rdone) ? imap_pkg::ROW_WRITE : imap_pkg::ROW_NONE;
          cw.rowm = 1'b1;
          cw.nrows = 4'(x_rows - x_rdone);
          cwx.addr = 20'(x_addr + x_rdone);
          xe_pf = (x_rows != x_rdone) && !x_last;
          xe_prow = x_ebase + x_rows;
        end else begin
          xe_wr = (x_rows != x_rdone);
          cw.row = ((x_rows != x_rdone) && !x_last) ? imap_pkg::ROW_READ : imap_pkg::ROW_NONE;
          cwx.addr = 20'(x_addr + x_rows);
        end
      end
    end

    // preloads for the instruction entering X at the end of this cycle
    if (d_adv && d_flt == imap_pkg::FLT_NONE) begin
      case (d_op)
        imap_pkg::OP_RXL, imap_pkg::OP_RXR: cw.pre = imap_pkg::PRE_RING;
        imap_pkg::OP_LDX, imap_pkg::OP_STX: begin
          cw.pre = imap_pkg::PRE_ADDR;
          cw_pre = d_ldxoff;
        end
        // ld reads its byte through the row port (byte 0 of the row)
        imap_pkg::OP_LD, imap_pkg::OP_VOUT, imap_pkg::OP_XST: cw.pre = imap_pkg::PRE_ROW;
        imap_pkg::OP_XLD: begin
          xe_pf = 1'b1;
          xe_prow = d_ca;
        end
        default: ;
      endcase
      if (d_op == imap_pkg::OP_VIN || d_op == imap_pkg::OP_VOUT) vid_open = 1'b1;
    end

    ev_cycle = count_now;
    ev_kind = x_v ? x_kind : imap_pkg::K_CP;
    ev_phase = phase_q;
    ev_pe = x_v && (x_kind == imap_pkg::K_ALU || x_kind == imap_pkg::K_MINMAX || x_kind == imap_pkg::K_SHIFT ||
                    x_kind == imap_pkg::K_MEM || x_kind == imap_pkg::K_MEMX || x_kind == imap_pkg::K_RING);
    ev_active = active_now;
    ev_retire = x_commit;
    ev_op = x_op;

    cw.act = cw.clr || cw.commit || cw.first || cw.step || cw.row != imap_pkg::ROW_NONE || cw.pre != imap_pkg::PRE_NONE;

    red_status = x_v && (x_op == imap_pkg::OP_RANY || x_op == imap_pkg::OP_RALL);
    red_memx = x_v && x_first && x_kind == imap_pkg::K_MEMX;
    red_count = m_dirty;
  end

  // ===========================================================================
  // Static part of the PE control word for an opcode (registered into X)
  // ===========================================================================
  // Static part of the PE control word of the instruction in D (registered
  // into X when it enters execute).
  imap_pkg::cw_t d_cw;
  always_comb begin
    d_cw = '0;
    d_cw.rd = d_rd[5:0];
    d_cw.ra = d_ra[5:0];
    d_cw.rb = d_rb[5:0];
    d_cw.imm = d_imm[7:0];
    d_cw.rd_we = 1'b1;
    // a row per opcode: the unit function and what differs from the defaults
    // above (rd written; C, T not written; no mask command)
    case (d_op)
      imap_pkg::OP_ADD, imap_pkg::OP_ADDI: begin d_cw.fn = imap_pkg::F_ADD; d_cw.c_we = 1'b1; end
      imap_pkg::OP_ADC, imap_pkg::OP_ADCI: begin d_cw.fn = imap_pkg::F_ADC; d_cw.c_we = 1'b1; end
      imap_pkg::OP_SUB, imap_pkg::OP_SUBI: begin d_cw.fn = imap_pkg::F_SUB; d_cw.c_we = 1'b1; end
      imap_pkg::OP_SBC, imap_pkg::OP_SBCI: begin d_cw.fn = imap_pkg::F_SBC; d_cw.c_we = 1'b1; end
      imap_pkg::OP_AND, imap_pkg::OP_ANDI: d_cw.fn = imap_pkg::F_AND;
      imap_pkg::OP_OR, imap_pkg::OP_ORI: d_cw.fn = imap_pkg::F_OR;
      imap_pkg::OP_XOR, imap_pkg::OP_XORI: d_cw.fn = imap_pkg::F_XOR;
      imap_pkg::OP_MIN, imap_pkg::OP_MINI: d_cw.fn = imap_pkg::F_MIN;
      imap_pkg::OP_MAX, imap_pkg::OP_MAXI: d_cw.fn = imap_pkg::F_MAX;
      imap_pkg::OP_MOV: d_cw.fn = imap_pkg::F_PASSA;
      imap_pkg::OP_LI: d_cw.fn = imap_pkg::F_PASSB;
      imap_pkg::OP_LC, imap_pkg::OP_LCB: begin d_cw.fn = imap_pkg::F_PASSB; d_cw.imm = d_byte; end
      imap_pkg::OP_PIDX: d_cw.fn = imap_pkg::F_PIDX;
      imap_pkg::OP_SETC: d_cw.fn = imap_pkg::F_SETC;
      imap_pkg::OP_SETT: d_cw.fn = imap_pkg::F_SETT;
      imap_pkg::OP_CSEL: d_cw.fn = imap_pkg::F_CSEL;
      imap_pkg::OP_TSEL: d_cw.fn = imap_pkg::F_TSEL;
      imap_pkg::OP_SHLI, imap_pkg::OP_SHLV: begin d_cw.fn = imap_pkg::F_SHL; d_cw.c_we = 1'b1; end
      imap_pkg::OP_SHRI, imap_pkg::OP_SHRV: begin d_cw.fn = imap_pkg::F_SHR; d_cw.c_we = 1'b1; end
      imap_pkg::OP_ROLC: begin d_cw.fn = imap_pkg::F_ROLC; d_cw.c_we = 1'b1; end
      imap_pkg::OP_RORC: begin d_cw.fn = imap_pkg::F_RORC; d_cw.c_we = 1'b1; end
      imap_pkg::OP_CEQ, imap_pkg::OP_CEQI, imap_pkg::OP_CNE, imap_pkg::OP_CNEI, imap_pkg::OP_CLTU, imap_pkg::OP_CLTUI, imap_pkg::OP_CLEU, imap_pkg::OP_CLEUI, imap_pkg::OP_CGTU,
          imap_pkg::OP_CGTUI, imap_pkg::OP_CGEU, imap_pkg::OP_CGEUI, imap_pkg::OP_TC, imap_pkg::OP_TNOT: begin
        d_cw.fn = imap_pkg::F_CMP;
        d_cw.rd_we = 1'b0;
        d_cw.t_we = 1'b1;
        case (d_op)
          imap_pkg::OP_CEQ, imap_pkg::OP_CEQI: d_cw.cmp = imap_pkg::CMP_EQ;
          imap_pkg::OP_CNE, imap_pkg::OP_CNEI: d_cw.cmp = imap_pkg::CMP_NE;
          imap_pkg::OP_CLTU, imap_pkg::OP_CLTUI: d_cw.cmp = imap_pkg::CMP_LT;
          imap_pkg::OP_CLEU, imap_pkg::OP_CLEUI: d_cw.cmp = imap_pkg::CMP_LE;
          imap_pkg::OP_CGTU, imap_pkg::OP_CGTUI: d_cw.cmp = imap_pkg::CMP_GT;
          imap_pkg::OP_CGEU, imap_pkg::OP_CGEUI: d_cw.cmp = imap_pkg::CMP_GE;
          imap_pkg::OP_TC: d_cw.cmp = imap_pkg::CMP_C;
          default: d_cw.cmp = imap_pkg::CMP_NOTT;
        endcase
      end
      imap_pkg::OP_LD: d_cw.fn = imap_pkg::F_LD;
      imap_pkg::OP_LDX: d_cw.fn = imap_pkg::F_LDX;
      imap_pkg::OP_ST: begin d_cw.fn = imap_pkg::F_ST; d_cw.rd_we = 1'b0; end
      imap_pkg::OP_STX: begin d_cw.fn = imap_pkg::F_STX; d_cw.rd_we = 1'b0; end
      imap_pkg::OP_RXL: begin d_cw.fn = imap_pkg::F_RING; d_cw.up = 1'b1; end
      imap_pkg::OP_RXR: d_cw.fn = imap_pkg::F_RING;
      imap_pkg::OP_MIF: begin d_cw.rd_we = 1'b0; d_cw.mask = imap_pkg::MK_IF; end
      imap_pkg::OP_MELSE: begin d_cw.rd_we = 1'b0; d_cw.mask = imap_pkg::MK_ELSE; end
      imap_pkg::OP_MEND: begin d_cw.rd_we = 1'b0; d_cw.mask = imap_pkg::MK_END; end
      imap_pkg::OP_MALL: begin d_cw.rd_we = 1'b0; d_cw.mask = imap_pkg::MK_ALL; end
      default: begin d_cw.fn = imap_pkg::F_NONE; d_cw.rd_we = 1'b0; end
    endcase
    // operand b: the immediate for the Rri8 / Cmpi / Ri8 / Rsh formats
    case (d_fmt)
      imap_pkg::FMT_RRI8, imap_pkg::FMT_CMPI, imap_pkg::FMT_RI8, imap_pkg::FMT_RSH, imap_pkg::FMT_RC, imap_pkg::FMT_RCK: d_cw.bimm = 1'b1;
      default: d_cw.bimm = 1'b0;
    endcase
  end

  // Cycles of the first sequencer step of an instruction entering X, minus 1.
  function automatic logic [31:0] first_count(input imap_pkg::kind_t k);
    case (k)
      imap_pkg::K_CP: first_count = straps.c_cp - 32'd1;
      imap_pkg::K_ALU: first_count = straps.c_alu - 32'd1;
      imap_pkg::K_MINMAX: first_count = straps.c_alu + straps.c_minmax_extra - 32'd1;
      imap_pkg::K_SHIFT: first_count = straps.c_alu - 32'd1;  // latency before the passes
      imap_pkg::K_MEM: first_count = straps.c_mem - 32'd1;
      imap_pkg::K_MEMX: first_count = straps.c_mem + straps.c_indirect_extra - 32'd1;
      imap_pkg::K_MASK: first_count = straps.c_mask - 32'd1;
      imap_pkg::K_STATUS: first_count = straps.c_status - 32'd1;
      imap_pkg::K_VIDEO: first_count = straps.c_video_line - 32'd1;
      imap_pkg::K_XFER: first_count = straps.c_xfer_setup - 32'd1;
      default: first_count = 32'd0;
    endcase
  endfunction

  // ===========================================================================
  // Sequential logic
  // ===========================================================================
  always_ff @(posedge clk) begin
    if (!rst_n) begin
      run_q <= 1'b0;
      clr_q <= 2'd3;
      f_pc <= '0;
      d_v <= 1'b0;
      x_v <= 1'b0;
      bub <= 32'd0;
      halted <= 1'b0;
      faulted <= 1'b0;
      mcycle <= 64'd0;
      instret <= 64'd0;
      csp <= 9'd0;
      msp <= 9'd0;
      phase_q <= 16'd0;
      m_active <= 17'(P);
      m_dirty <= 1'b0;
      for (int i = 0; i < 16; i++) creg[i] <= 32'h0;
      if (host.we) begin
        if (host.sel) param[host.addr[7:0]] <= host.data[31:0];
        else imem[host.addr[$clog2(IMEM_WORDS)-1:0]] <= host.data;
      end
    end else begin
      if (clr_q != 2'd0) clr_q <= clr_q - 2'd1;
      else if (!halted && !faulted) run_q <= 1'b1;

      // ---- machine cycle
      if (count_now) mcycle <= mcycle + 64'd1;
      if (m_dirty) begin
        m_active <= active_n;
        m_dirty <= 1'b0;
      end
      if (bub != 32'd0) bub <= bub - 32'd1;

      // ---- X: fault in the first cycle
      if (x_v && x_first && x_flt != imap_pkg::FLT_NONE && run_q) begin
        faulted <= 1'b1;
        run_q <= 1'b0;
        f_code <= x_flt;
        f_pc_q <= x_pc;
        f_cyc <= mcycle;
        f_pe <= x_fpe;
        f_addr <= x_fad;
      end

      // ---- X: the sequencer
      if (x_v && run_q && !(x_first && x_flt != imap_pkg::FLT_NONE)) begin
        x_first <= 1'b0;
        case (x_kind)
          imap_pkg::K_SHIFT: begin
            if (x_step) begin
              x_shpass <= 1'b1;
              x_shrem <= (x_shrem > sb) ? x_shrem - sb : 3'd0;
            end else x_cnt <= x_cnt - 32'd1;
          end
          imap_pkg::K_RING: begin
            if (x_step) begin
              x_hcyc <= straps.c_ring_hop;
              x_hops <= x_hops - 17'd1;
            end else x_hcyc <= x_hcyc - 32'd1;
          end
          imap_pkg::K_XFER: begin
            x_act <= xa_now;
            if (x_setup) begin
              x_brem <= xb_now;
              if (x_cnt == 32'd0) x_setup <= 1'b0;
              else x_cnt <= x_cnt - 32'd1;
            end else if (x_beat != 32'd0) begin
              x_brem <= xb_now;
              x_beat <= x_beat - 32'd1;
            end else begin
              x_cred <= x_credn;
              x_rdone <= x_rows;
              x_brem <= x_last ? 48'd0 : xb_now - 48'(straps.c_ext_bpc);
              x_beat <= straps.c_ext_beat - 32'd1;
            end
          end
          default: if (x_cnt != 32'd0 && !x_vwait) x_cnt <= x_cnt - 32'd1;
        endcase
      end

      // ---- X: commit of the CP side and the retire record
      if (x_commit) begin
        instret <= instret + 64'd1;
        if (x_cwe) creg[x_cidx] <= x_cres;
        case (x_op)
          imap_pkg::OP_CST: param[x_addr[7:0]] <= creg[x_ir[11:8]];
          imap_pkg::OP_CALL: begin
            cstk[csp[$clog2(CALL_DEPTH)-1:0]] <= x_pc[PCW-1:0] + 1'b1;
            csp <= csp + 9'd1;
          end
          imap_pkg::OP_RET: csp <= csp - 9'd1;
          imap_pkg::OP_PHASE: phase_q <= x_ir[47:32];
          imap_pkg::OP_HALT: begin
            halted <= 1'b1;
            run_q <= 1'b0;
          end
          default: ;
        endcase
        msp <= msp_next;
        if (x_kind == imap_pkg::K_MASK) m_dirty <= 1'b1;
        if (x_bubble) bub <= straps.c_branch_taken;
      end

      // ---- D -> X
      if (x_commit || !x_v) x_v <= 1'b0;
      if (d_adv) begin
        x_v <= 1'b1;
        x_first <= 1'b1;
        x_pc <= d_pc;
        x_ir <= d_ir;
        x_op <= d_op;
        x_kind <= d_kind;
        x_dflt <= d_flt;
        // ldx / stx: the broadcast part of the per-PE address (cN + off), to
        // which the failing PE's offset is added for the fault report
        x_faddr <= (d_op == imap_pkg::OP_LDX || d_op == imap_pkg::OP_STX) && d_flt == imap_pkg::FLT_NONE
                   ? {{32{d_ldxoff[31]}}, d_ldxoff} : d_faddr;
        x_a <= (d_op == imap_pkg::OP_CST) ? d_cd : d_ca;
        x_b <= d_cb;
        x_addr <= d_addr[31:0];
        x_taken <= d_taken;
        x_cw <= d_cw;
        x_cyc0 <= count_now ? mcycle + 64'd1 : mcycle;
        x_cnt <= first_count(d_kind);
        x_zero <= (d_kind == imap_pkg::K_PHASE) ||
            (d_kind == imap_pkg::K_XFER && straps.c_xfer_setup == 32'd0 && d_cd == 32'd0);
        // shifter: bits to shift (7 for the per-PE amounts of shlv / shrv)
        x_shrem <= (d_op == imap_pkg::OP_SHLV || d_op == imap_pkg::OP_SHRV) ? 3'd7 : d_imm[2:0];
        x_shpass <= 1'b0;
        // ring
        x_hops <= d_imm[16:0];
        x_hcyc <= straps.c_ring_hop;
        // transfer engine
        x_setup <= (straps.c_xfer_setup != 32'd0);
        x_beat <= straps.c_ext_beat - 32'd1;
        x_brem <= 48'd0;  // counted in the first cycle (xb_now)
        x_cred <= 32'd0;
        x_rdone <= 32'd0;
        x_ebase <= d_ca;
        x_len <= d_cd;
        x_xst <= (d_op == imap_pkg::OP_XST);
        // video
        x_vport <= d_rd[0];
        x_vy <= d_cy;
        x_vx <= d_cx;
      end

      // ---- F -> D
      if (run_q && (d_adv || !d_v)) begin
        fa = (d_adv && d_taken && d_flt == imap_pkg::FLT_NONE) ? d_target : f_pc;
        d_v <= 1'b1;
        d_pc <= fa;
        d_ir <= (32'(fa) < straps.cfg_prog_len) ? imem[fa[$clog2(IMEM_WORDS)-1:0]] : 64'h0;
        f_pc <= fa + 1;
      end
    end
  end

`ifndef SYNTHESIS
  // ===========================================================================
  // Assertions (docs/rtl.md, "Assertions"): read-only checks of the CP's
  // invariants, sampled at each rising edge (the values of the cycle ending
  // there). They change nothing the design computes.
  // ===========================================================================
  logic cw_ok;
  logic [31:0] a_base;
  always_ff @(posedge clk)
    if (rst_n) begin
      // ---- control-word legality: what the PEs are told to do in a cycle
      // of an instruction is one of the things they can do
      if (run_q && (cw.commit || cw.step || cw.first) &&
          !(x_v && x_first && x_flt != imap_pkg::FLT_NONE)) begin
        cw_ok = !cw.clr && cw.fn <= imap_pkg::F_RING &&
            cw.mask <= imap_pkg::MK_ALL && cw.sbits != 3'd0;
        if (cw.rd_we || cw.c_we || cw.t_we) cw_ok = cw_ok && cw.mask == imap_pkg::MK_NONE;
        if (cw.rd_we) cw_ok = cw_ok && 8'(cw.rd) < straps.cfg_pe_regs && 32'(cw.rd) < NREGS;
        if (cw.step) cw_ok = cw_ok && (cw.fn == imap_pkg::F_SHL || cw.fn == imap_pkg::F_SHR ||
                                       cw.fn == imap_pkg::F_RING);
        if (cw.first) cw_ok = cw_ok && (cw.fn == imap_pkg::F_SHL || cw.fn == imap_pkg::F_SHR);
        a_cw_legal :
        assert (cw_ok)
        else `IMAP_FAIL(a_cw_legal, -1);
      end
      if (cw.row != imap_pkg::ROW_NONE)
        a_cw_row_legal :
        assert (cw.row != 2'd3 && 32'(cw.nrows) <= XROWS &&
                (cw.row != imap_pkg::ROW_WRITE || cw.nrows != 4'd0))
        else `IMAP_FAIL(a_cw_row_legal, -1);

      // ---- the mask and return stacks: an instruction that would overflow
      // or underflow them faults before it commits (docs/isa.md 4.1)
      if (x_commit)
        case (x_op)
          imap_pkg::OP_MIF:
          a_mask_ovf :
          assert (msp < straps.cfg_mask_depth && 32'(msp) < MASK_DEPTH)
          else `IMAP_FAIL(a_mask_ovf, -1);
          imap_pkg::OP_MELSE, imap_pkg::OP_MEND:
          a_mask_unf :
          assert (msp != 9'd0)
          else `IMAP_FAIL(a_mask_unf, -1);
          imap_pkg::OP_CALL:
          a_call_ovf :
          assert (csp < straps.cfg_call_depth && 32'(csp) < CALL_DEPTH)
          else `IMAP_FAIL(a_call_ovf, -1);
          imap_pkg::OP_RET:
          a_call_unf :
          assert (csp != 9'd0)
          else `IMAP_FAIL(a_call_unf, -1);
          default: ;
        endcase

      // ---- decode's forwarding: the CP operands an instruction took in D
      // (cA, cB and the address cB + off) are the register file's values
      // once everything before it has committed, i.e. in its first cycle
      if (x_v && x_first && run_q) begin
        a_base = (x_ir[31:24] == 8'd128) ? 32'h0 : creg[x_ir[27:24]];
        a_cp_operands :
        assert (x_b == creg[x_ir[27:24]] && x_addr == a_base + x_ir[63:32] &&
                x_a == creg[(x_op == imap_pkg::OP_CST) ? x_ir[11:8] : x_ir[19:16]])
        else `IMAP_FAIL(a_cp_operands, -1);
      end

      // ---- the transfer engine (xld / xst)
      if (x_v && run_q && x_kind == imap_pkg::K_XFER) begin
        // rows written into / read from the local memory stay inside the
        // transfer's range [cB + off, + len), which is inside the memory
        if (cw.row == imap_pkg::ROW_WRITE)
          a_xfer_local :
          assert (64'(x_addr) + 64'(x_len) <= 64'(MEM_BYTES) &&
                  64'(cwx.addr) + 64'(cw.nrows) <= 64'(x_addr) + 64'(x_len) &&
                  64'(cwx.addr) >= 64'(x_addr))
          else `IMAP_FAIL(a_xfer_local, -1);
        // rows written into the external memory: inside [cA, + len), inside it
        if (xe_wr)
          a_xfer_ext :
          assert (64'(x_ebase) + 64'(x_len) <= 64'(EXT_BYTES) &&
                  64'(xe_wrow) + 64'(xe_n) <= 64'(x_ebase) + 64'(x_len) &&
                  xe_wrow >= x_ebase)
          else `IMAP_FAIL(a_xfer_ext, -1);
        // a transfer that moves bytes moves all its rows: at its last data
        // cycle the rows done are its length
        if (x_commit && !x_zn && !x_setup)
          a_xfer_rows :
          assert (x_rows == x_len)
          else `IMAP_FAIL(a_xfer_rows, -1);
      end
    end

  // ---- the pipeline: a taken branch is followed by c_branch_taken refill
  // bubbles (X empty, the bubble counter loaded) before the next
  // instruction enters execute; a halted or faulted machine retires
  // nothing more; the stack depths stay within the configuration
  a_cp_refill :
  assert property (@(posedge clk) disable iff (!rst_n)
                   (x_commit && x_taken && straps.c_branch_taken != 32'd0) |=>
                   (!x_v && bub == straps.c_branch_taken))
  else `IMAP_FAIL(a_cp_refill, -1);
  a_cp_stopped :
  assert property (@(posedge clk) disable iff (!rst_n)
                   !(halted && faulted) && !((halted || faulted) && x_commit))
  else `IMAP_FAIL(a_cp_stopped, -1);
  a_stack_depth :
  assert property (@(posedge clk) disable iff (!rst_n)
                   msp <= straps.cfg_mask_depth && csp <= straps.cfg_call_depth)
  else `IMAP_FAIL(a_stack_depth, -1);
`endif

endmodule
