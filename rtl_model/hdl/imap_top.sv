`include "imap_mutants.svh"
// IMAP-VISION array, top level of the register-transfer design: the control
// processor, the PE array (P PEs with the ring and the mask bus) and the
// board (external memory, video port). Every cost-table entry and the
// run-time machine configuration are strap inputs; the sizes are
// parameters (docs/rtl.md, "Configurations").
module imap_top
#(
    parameter int P = 8,  // PEs (pes)
    parameter int MEM_BYTES = 1024,  // local memory per PE (mem_bytes)
    parameter int EXT_BYTES = 65536,  // external memory per PE (ext_bytes)
    parameter int NREGS = 16,  // registers per PE (at least pe_regs)
    parameter int MASK_DEPTH = 8,  // mask stack (at least mask_depth)
    parameter int CALL_DEPTH = 16,  // return stack (at least call_depth)
    parameter int IMEM_WORDS = 65536,  // instruction memory
    parameter int XROWS = 4,  // rows per cycle of the transfer path (ext_bytes_per_cycle <= XROWS * P)
    parameter int PHASES = 256  // per-phase cycle counters
) (
    input logic clk,
    input logic rst_n,
`ifdef IMAP_MUTANTS
    input logic [7:0] mutant,  // planted bug (mutation check)
`endif
    input logic host_we,
    input logic host_sel,
    input logic [23:0] host_addr,
    input logic [63:0] host_data,
    input logic [31:0] c_alu,
    input logic [31:0] c_mem,
    input logic [31:0] c_indirect_extra,
    input logic [31:0] c_ring_hop,
    input logic [31:0] c_mask,
    input logic [31:0] c_status,
    input logic [31:0] c_cp,
    input logic [31:0] c_branch_taken,
    input logic [31:0] c_video_line,
    input logic [31:0] c_xfer_setup,
    input logic [31:0] c_ext_bpc,
    input logic [31:0] c_shift_bits,
    input logic [31:0] c_minmax_extra,
    input logic [31:0] cfg_prog_len,
    input logic [7:0] cfg_pe_regs,
    input logic [8:0] cfg_mask_depth,
    input logic [8:0] cfg_call_depth,
    input logic cfg_indirect,
    input logic cfg_ext_on,
    input logic [63:0] cfg_watchdog,
    input logic cfg_trace,
    output logic done
);


  imap_pkg::cw_t cw;
  imap_pkg::cwx_t cwx;
  logic [31:0] cw_pre;
  logic red_status, red_memx, red_count, any_t, all_t, memx_bad;
  logic [15:0] memx_pe, memx_off;
  logic [16:0] active_n;
  logic xe_pf, xe_wr, vid_open, vid_out, vid_put;
  logic [31:0] xe_prow, xe_wrow, vid_oy, vid_ox, vid_py, vid_px;
  logic [2:0] xe_n;
  logic [0:0] vid_oport, vid_pport;
  logic [1:0] vid_status;
  logic [P*XROWS*8-1:0] rbus;  // row bus: PE p reads slice p
  logic [XROWS*8-1:0] rrow[P];
  logic halted, faulted;
  logic [63:0] mcycle;
  logic ev_cycle, ev_pe, ev_retire;
  imap_pkg::kind_t ev_kind;
  logic [15:0] ev_phase;
  logic [16:0] ev_active;
  logic [7:0] ev_op;


  // Configuration registers: the straps are sampled while rst_n = 0 and held
  // during the run (the design's logic depends on registers only).
  logic [31:0] c_alu_q, c_mem_q, c_indirect_extra_q, c_ring_hop_q, c_mask_q, c_status_q, c_cp_q, c_branch_taken_q, c_video_line_q, c_xfer_setup_q, c_ext_bpc_q, c_shift_bits_q, c_minmax_extra_q, cfg_prog_len_q;
  logic [7:0] cfg_pe_regs_q;
  logic [8:0] cfg_mask_depth_q, cfg_call_depth_q;
  logic cfg_indirect_q, cfg_ext_on_q, cfg_trace_q;
  logic [63:0] cfg_watchdog_q;
`ifdef IMAP_MUTANTS
  logic [7:0] mutant_q;
`endif
  always_ff @(posedge clk)
    if (!rst_n) begin
      c_alu_q <= c_alu;
      c_mem_q <= c_mem;
      c_indirect_extra_q <= c_indirect_extra;
      c_ring_hop_q <= c_ring_hop;
      c_mask_q <= c_mask;
      c_status_q <= c_status;
      c_cp_q <= c_cp;
      c_branch_taken_q <= c_branch_taken;
      c_video_line_q <= c_video_line;
      c_xfer_setup_q <= c_xfer_setup;
      c_ext_bpc_q <= c_ext_bpc;
      c_shift_bits_q <= c_shift_bits;
      c_minmax_extra_q <= c_minmax_extra;
      cfg_prog_len_q <= cfg_prog_len;
      cfg_pe_regs_q <= cfg_pe_regs;
      cfg_mask_depth_q <= cfg_mask_depth;
      cfg_call_depth_q <= cfg_call_depth;
      cfg_indirect_q <= cfg_indirect;
      cfg_ext_on_q <= cfg_ext_on;
      cfg_trace_q <= cfg_trace;
      cfg_watchdog_q <= cfg_watchdog;
`ifdef IMAP_MUTANTS
      mutant_q <= mutant;
`endif
    end

  imap_cp #(
      .P(P),
      .MEM_BYTES(MEM_BYTES),
      .EXT_BYTES(EXT_BYTES),
      .NREGS(NREGS),
      .MASK_DEPTH(MASK_DEPTH),
      .CALL_DEPTH(CALL_DEPTH),
      .IMEM_WORDS(IMEM_WORDS),
      .XROWS(XROWS),
      .PHASES(PHASES)
  ) u_cp (
      .c_alu(c_alu_q),
      .c_mem(c_mem_q),
      .c_indirect_extra(c_indirect_extra_q),
      .c_ring_hop(c_ring_hop_q),
      .c_mask(c_mask_q),
      .c_status(c_status_q),
      .c_cp(c_cp_q),
      .c_branch_taken(c_branch_taken_q),
      .c_video_line(c_video_line_q),
      .c_xfer_setup(c_xfer_setup_q),
      .c_ext_bpc(c_ext_bpc_q),
      .c_shift_bits(c_shift_bits_q),
      .c_minmax_extra(c_minmax_extra_q),
      .cfg_prog_len(cfg_prog_len_q),
      .cfg_pe_regs(cfg_pe_regs_q),
      .cfg_mask_depth(cfg_mask_depth_q),
      .cfg_call_depth(cfg_call_depth_q),
      .cfg_indirect(cfg_indirect_q),
      .cfg_ext_on(cfg_ext_on_q),
      .cfg_trace(cfg_trace_q),
      .cfg_watchdog(cfg_watchdog_q),
`ifdef IMAP_MUTANTS
      .mutant(mutant_q),
`endif
      .*
  );

  imap_array #(
      .P(P),
      .NREGS(NREGS),
      .MEM_BYTES(MEM_BYTES),
      .MASK_DEPTH(MASK_DEPTH),
      .XROWS(XROWS)
  ) u_array (
`ifdef IMAP_MUTANTS
      .mutant(mutant_q),
`endif
      .*
  );

  imap_board #(
      .P(P),
      .EXT_BYTES(EXT_BYTES),
      .XROWS(XROWS)
  ) u_board (
      .trace(cfg_trace_q),
      .*
  );

  imap_perf #(.PHASES(PHASES)) u_perf (.*);

  assign done = halted | faulted;

endmodule
