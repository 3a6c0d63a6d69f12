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
`include "imap_ports.svh"
module imap_top
#(
`include "imap_params.svh"
) (
    `IMAP_CLOCK_PORTS
    input imap_pkg::host_t host,  // the host port (program and param block)
    input imap_pkg::straps_t straps,  // the cost table and the machine configuration
    output logic done,
    // board: external-memory row interface (prefetch xe_pf of XROWS rows from
    // xe_prow onto rbus; write xe_wr of xe_n rows at xe_wrow from rrow)
    output logic xe_pf,
    output logic [31:0] xe_prow,
    output logic xe_wr,
    output logic [31:0] xe_wrow,
    output logic [3:0] xe_n,
    output logic [P-1:0] xe_pm,  // the PEs' M bits (xst writes the active PEs' bytes)
    output logic [P*XROWS*8-1:0] rrow,  // PE p: slice p
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
  imap_pkg::straps_t straps_q;
`ifdef IMAP_MUTANTS
  logic [7:0] mutant_q;
`endif
  always_ff @(posedge clk)
    if (!rst_n) begin
      straps_q <= straps;
`ifdef IMAP_MUTANTS
      mutant_q <= mutant;
`endif
    end

  imap_cp #(`IMAP_PARAMS_PASS) u_cp (
      .straps(straps_q),
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

`ifndef IMAP_NO_PERF
  // the testbench's counters (left out of the place-and-route harness of the
  // chip, rtl_model/synth/pnr_chip.sv: 512 64-bit counters are not the chip)
  imap_perf #(.PHASES(PHASES)) u_perf (.*);
`endif

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
