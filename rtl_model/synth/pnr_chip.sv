// Place-and-route harness of the whole chip (scripts/rtl-pnr.sh, docs/rtl.md,
// "Place and route (iCE40)"): not part of the design. imap_top (CP, P PEs
// with their local memories, ring, mask bus, performance counters) with:
//   - the straps tied to one machine: the cost table and configuration of
//     docs/isa.md 2.2's defaults (a chip is built for one cost table; the
//     simulated design keeps them as inputs for the what-ifs), so synthesis
//     folds the logic that only other cost tables need;
//   - the performance counters left out (IMAP_NO_PERF: they are the
//     testbench's instruments, 512 counters of 64 bits);
//   - every other input (host port, reset, board rows and video status)
//     fed from one serial shift register (pin sin), every output folded into
//     one registered XOR (pin sout), as in pnr_pe.sv.
module imap_pnr_chip #(
    parameter int P = 2,
    parameter int MEM_BYTES = 256,
    parameter int EXT_BYTES = 256,
    parameter int IMEM_WORDS = 256
) (
    input  logic clk,
    sin,
    output logic sout
);
  localparam int XROWS = 8;
  imap_pkg::straps_t straps;
  always_comb begin
    straps = '0;
    straps.c_alu = 32'd1;
    straps.c_mem = 32'd1;
    straps.c_indirect_extra = 32'd1;
    straps.c_ring_hop = 32'd1;
    straps.c_mask = 32'd1;
    straps.c_status = 32'd1;
    straps.c_cp = 32'd1;
    straps.c_branch_taken = 32'd1;
    straps.c_video_line = 32'd1;
    straps.c_xfer_setup = 32'd8;
    straps.c_ext_bpc = 32'd1;
    straps.c_ext_beat = 32'd1;
    straps.c_shift_bits = 32'd7;
    straps.c_minmax_extra = 32'd0;
    straps.cfg_prog_len = 32'(IMEM_WORDS);
    straps.cfg_pe_regs = 8'd16;
    straps.cfg_mask_depth = 9'd8;
    straps.cfg_call_depth = 9'd8;
    straps.cfg_indirect = 1'b1;
    straps.cfg_ext_on = 1'b1;
    straps.cfg_watchdog = 64'd0;
    straps.cfg_trace = 1'b0;
  end

  logic rst_n;
  imap_pkg::host_t host;
  logic [P*XROWS*8-1:0] rbus;
  logic [1:0] vid_status;
  logic [63:0] vid_ready;
  localparam int WI = 1 + $bits(host) + P * XROWS * 8 + 2 + 64;
  logic [WI-1:0] sh;
  always_ff @(posedge clk) sh <= {sh[WI-2:0], sin};
  assign {rst_n, host, rbus, vid_status, vid_ready} = sh;

  logic done, xe_pf, xe_wr, vid_open, vid_out, vid_put;
  logic [31:0] xe_prow, xe_wrow, vid_oy, vid_ox, vid_py, vid_px;
  logic [3:0] xe_n;
  logic [P-1:0] xe_pm;
  logic [P*XROWS*8-1:0] rrow;
  logic [0:0] vid_oport, vid_pport;
  imap_top #(
      .P(P),
      .MEM_BYTES(MEM_BYTES),
      .EXT_BYTES(EXT_BYTES),
      .IMEM_WORDS(IMEM_WORDS)
  ) u_chip (
      .*
  );
  always_ff @(posedge clk)
    sout <= ^{done, xe_pf, xe_wr, vid_open, vid_out, vid_put, xe_prow, xe_wrow, vid_oy, vid_ox,
              vid_py, vid_px, xe_n, xe_pm, rrow, vid_oport, vid_pport};
endmodule
