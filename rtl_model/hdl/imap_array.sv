`include "imap_mutants.svh"
`include "imap_assert.svh"
// The PE array: P PE modules, the shift ring as wires between neighbours
// (PE p's ring register drives the nb_hi input of PE p-1 and the nb_lo input
// of PE p+1; PE 0 and PE P-1 close the ring), the mask bus (status
// reduction of T over the active PEs for rany / rall, the ldx / stx address
// check, the count of active PEs) and the row buses of the video line and
// external-memory transfer units.
`include "imap_ports.svh"
module imap_array
#(
    parameter int P = 8,
    parameter int NREGS = 16,
    parameter int MEM_BYTES = 1024,
    parameter int MASK_DEPTH = 8,
    parameter int XROWS = 8
) (
    input logic clk,
    `IMAP_MUTANT_PORT
    input imap_pkg::cw_t cw,
    input imap_pkg::cwx_t cwx,
    input logic [31:0] cw_pre,
    input logic [P*XROWS*8-1:0] rbus,  // row bus into the PEs (PE p: slice p)
    output logic [P*XROWS*8-1:0] rrow,  // the PEs' row read ports (PE p: slice p)
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
  logic [XROWS*8-1:0] prow[P];  // each PE's row read port (gathered onto rrow below)

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
        .row_q(prow[p])
    );
  end

  // The row read ports as one bus (a flat port: yosys reads no array port).
  // Slice by slice: the simulator then writes each PE's 8 bytes in place
  // rather than re-concatenating the whole P x 8-byte bus.
  always_comb for (int p = 0; p < P; p++) rrow[p*XROWS*8+:XROWS*8] = prow[p];

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

`ifndef SYNTHESIS
  // ---- assertions (docs/rtl.md, "Assertions")
  // The ring rotates: after a hop every PE's ring register holds what its
  // neighbour's held before it (rxl: PE p-1's, rxr: PE p+1's; PE 0 and PE
  // P-1 close the ring). Checked at the edge after the hop (a hop at the
  // edge where the next ring instruction preloads its source is left out).
  // The mask bus: rany / rall reduce T over exactly the active PEs; an
  // ldx / stx address fault names an active PE whose address is out of
  // range, and there is one exactly when such a PE exists.
  logic hop_q, hop_up_q;
  logic [7:0] ring_prev[P];
  int n_act, n_t;
  logic bad_any, named_ok;
  always_ff @(posedge clk) begin
    hop_q <= cw.act && cw.step && cw.fn == imap_pkg::F_RING && cw.pre != imap_pkg::PRE_RING &&
        !cw.clr;
    hop_up_q <= cw.up;
    if (cw.act && cw.step && cw.fn == imap_pkg::F_RING) ring_prev <= ring;
    if (hop_q)
      for (int p = 0; p < P; p++)
        a_ring_rotate :
        assert (ring[p] == ring_prev[hop_up_q ? (p + P - 1) % P : (p + 1) % P])
        else `IMAP_FAIL(a_ring_rotate, p);
    if (red_status) begin
      n_act = 0;
      n_t = 0;
      for (int p = 0; p < P; p++) begin
        if (st[p][0]) n_act = n_act + 1;
        if (st[p][0] && st[p][1]) n_t = n_t + 1;
      end
      a_maskbus_status :
      assert (all_t == (n_t == n_act) && any_t == (n_t != 0))
      else `IMAP_FAIL(a_maskbus_status, -1);
    end
    if (red_memx) begin
      bad_any = 1'b0;
      named_ok = 1'b0;
      for (int p = 0; p < P; p++) begin
        bad_any = bad_any | (st[p][2] & st[p][0]);
        if (32'(memx_pe) == p) named_ok = st[p][2] & st[p][0];
      end
      a_maskbus_memx :
      assert (memx_bad == bad_any && (!memx_bad || named_ok))
      else `IMAP_FAIL(a_maskbus_memx, memx_bad ? int'(memx_pe) : -1);
    end
  end
`endif

endmodule
