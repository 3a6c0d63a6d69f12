`include "imap_mutants.svh"
`include "imap_assert.svh"
// IMAP-VISION array, top level of the register-transfer design (the chip):
// the control processor, the PE array (P PEs with the ring and the mask bus)
// and the performance counters. The board (external memory, video port) is
// outside the chip: the chip drives its row interface and video handshake
// through the ports below (the external-memory rows and the video line
// port of docs/isa.md). Every cost-table entry and the
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
    parameter int XROWS = 8,  // rows per cycle of the transfer path (ext_bytes_per_cycle <= XROWS)
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
    input logic [31:0] c_ext_beat,
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
    output logic done,
    // board: external-memory row interface (prefetch xe_pf of XROWS rows from
    // xe_prow onto rbus; write xe_wr of xe_n rows at xe_wrow from rrow)
    output logic xe_pf,
    output logic [31:0] xe_prow,
    output logic xe_wr,
    output logic [31:0] xe_wrow,
    output logic [3:0] xe_n,
    output logic [P-1:0] xe_pm,  // the PEs' M bits (xst writes the active PEs' bytes)
    output logic [XROWS*8-1:0] rrow[P],
    input logic [P*XROWS*8-1:0] rbus,  // row bus: PE p reads slice p
    // board: video line port (vid_open when vin / vout enters execute, the
    // board answers vid_status at the next edge and loads a vin line onto
    // rbus; vid_put sends rrow's lane 0 when vout commits)
    output logic vid_open,
    output logic vid_out,
    output logic [0:0] vid_oport,
    output logic [31:0] vid_oy,
    output logic [31:0] vid_ox,
    output logic vid_put,
    output logic [0:0] vid_pport,
    output logic [31:0] vid_py,
    output logic [31:0] vid_px,
    input logic [1:0] vid_status,
    input logic [63:0] vid_ready
);


  imap_pkg::cw_t cw;
  imap_pkg::cwx_t cwx;
  logic [31:0] cw_pre;
  logic red_status, red_memx, red_count, any_t, all_t, memx_bad;
  logic [15:0] memx_pe, memx_off;
  logic [16:0] active_n;
  logic halted, faulted;
  logic [63:0] mcycle;
  logic ev_cycle, ev_pe, ev_retire;
  imap_pkg::kind_t ev_kind;
  logic [15:0] ev_phase;
  logic [16:0] ev_active;
  logic [7:0] ev_op;


  // Configuration registers: the straps are sampled while rst_n = 0 and held
  // during the run (the design's logic depends on registers only).
  logic [31:0] c_alu_q, c_mem_q, c_indirect_extra_q, c_ring_hop_q, c_mask_q, c_status_q, c_cp_q, c_branch_taken_q, c_video_line_q, c_xfer_setup_q, c_ext_bpc_q, c_ext_beat_q, c_shift_bits_q, c_minmax_extra_q, cfg_prog_len_q;
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
      c_ext_beat_q <= c_ext_beat;
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
      .c_ext_beat(c_ext_beat_q),
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

  imap_perf #(.PHASES(PHASES)) u_perf (.*);

  assign done = halted | faulted;

`ifndef SYNTHESIS
  // ---- assertion (docs/rtl.md, "Assertions"): the transfer engine counts
  // the bytes of the active PEs, and the row interface writes the external
  // memory of the active PEs: in the first cycle of an xld / xst, the CP's
  // count of active PEs (its cached mask-bus count) is the number of PEs
  // whose M bit the row interface carries (xe_pm)
  always_ff @(posedge clk)
    if (rst_n && u_cp.x_v && u_cp.x_first && u_cp.run_q && u_cp.x_kind == imap_pkg::K_XFER)
      a_xfer_active :
      assert (32'(u_cp.xa_now) == $countones(xe_pm))
      else `IMAP_FAIL(a_xfer_active, -1);
`endif

endmodule
