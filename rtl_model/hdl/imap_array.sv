`include "imap_mutants.svh"
// The PE array: P PE modules, the shift ring as wires between neighbours
// (PE p's ring register drives the nb_hi input of PE p-1 and the nb_lo input
// of PE p+1; PE 0 and PE P-1 close the ring), the mask bus (status
// reduction of T over the active PEs for rany / rall, the ldx / stx address
// check, the count of active PEs) and the row buses of the video line and
// external-memory transfer units.
module imap_array
#(
    parameter int P = 8,
    parameter int NREGS = 16,
    parameter int MEM_BYTES = 1024,
    parameter int MASK_DEPTH = 8,
    parameter int XROWS = 8
) (
    input logic clk,
`ifdef IMAP_MUTANTS
    input logic [7:0] mutant,  // planted bug (mutation check)
`endif
    input imap_pkg::cw_t cw,
    input imap_pkg::cwx_t cwx,
    input logic [31:0] cw_pre,
    input logic [P*XROWS*8-1:0] rbus,  // row bus into the PEs (PE p: slice p)
    output logic [XROWS*8-1:0] rrow[P],  // the PEs' row read ports
    // mask bus
    input logic red_status,  // rany / rall in execute
    input logic red_memx,  // ldx / stx in execute: check the preloaded addresses
    input logic red_count,  // count the active PEs
    output logic any_t,  // OR of T over the active PEs
    output logic all_t,  // AND of T over the active PEs (1 when none is active)
    output logic memx_bad,  // an active PE's ldx / stx address is out of range
    output logic [15:0] memx_pe,  // the first such PE
    output logic [15:0] memx_off,  // and its per-PE offset (rb:ra)
    output logic [16:0] active_n,  // PEs with M = 1 (valid with red_count)
    output logic [P-1:0] xe_pm  // each PE's M: the board writes xst rows of the active PEs only
);


  logic [7:0] ring[P];
  logic [2:0] st[P];
  logic [15:0] xoff[P];

  for (genvar p = 0; p < P; p++) begin : g_pe
    // ring neighbours: nb_lo = PE p-1 (rxl moves data to higher indices),
    // nb_hi = PE p+1; the ends wrap around
    localparam int LO = (p + P - 1) % P;
    localparam int HI = (p + 1) % P;
    imap_pe #(
        .NREGS(NREGS),
        .MEM_BYTES(MEM_BYTES),
        .MASK_DEPTH(MASK_DEPTH),
        .XROWS(XROWS)
    ) u_pe (
        .clk(clk),
`ifdef IMAP_MUTANTS
        .mutant(mutant),
`endif
        .cw(cw),
        .cwx(cwx),
        .cw_pre(cw_pre),
        .pe_index(16'(p)),
        .nb_lo(ring[LO]),
        .nb_hi((p == P - 1 && `IMAP_MUT(3)) ? 8'h00 : ring[HI]),
        .row_in(rbus[p*XROWS*8+:XROWS*8]),
        .ring_q(ring[p]),
        .st_q(st[p]),
        .xoff_q(xoff[p]),
        .row_q(rrow[p])
    );
  end

  // The mask bus reductions: evaluated only while an instruction needs them.
  always_comb begin
    any_t = 1'b0;
    all_t = 1'b1;
    memx_bad = 1'b0;
    memx_pe = 16'h0;
    memx_off = 16'h0;
    active_n = 17'h0;
    if (red_status)
      for (int p = 0; p < P; p++) begin
        any_t = any_t | (st[p][1] & st[p][0]);
        all_t = all_t & (st[p][1] | (~st[p][0] & ~`IMAP_MUT(8)));
      end
    if (red_memx)
      for (int p = P - 1; p >= 0; p--)
        if (st[p][2] && st[p][0]) begin
          memx_bad = 1'b1;
          memx_pe = 16'(p);
          memx_off = xoff[p];
        end
    if (red_count) for (int p = 0; p < P; p++) active_n = active_n + 17'(st[p][0]);
  end

  for (genvar p = 0; p < P; p++) begin : g_pm
    assign xe_pm[p] = st[p][0] | `IMAP_MUT(15);
  end

endmodule
