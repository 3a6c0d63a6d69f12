// Performance counters of the machine (not part of the synthesized CP): the
// cycles per sequencer kind, per phase, the executions per opcode, the
// cycles of PE instructions and the active PEs summed over them (PE
// utilisation). The testbench reads them through the backdoor at the end.
module imap_perf
#(
    parameter int PHASES = 256
) (
    input logic clk,
    input logic rst_n,
    input logic ev_cycle,
    input imap_pkg::kind_t ev_kind,
    input logic [15:0] ev_phase,
    input logic ev_pe,
    input logic [16:0] ev_active,
    input logic ev_retire,
    input logic [7:0] ev_op
);

  // Only the backdoor reads these: blocking writes keep the reset loops
  // simple for the simulator.
  logic [63:0] kind_cyc[imap_pkg::NKINDS]  /*verilator public_flat_rd*/;
  logic [63:0] op_cnt[256]  /*verilator public_flat_rd*/;
  logic [63:0] phase_cyc[PHASES]  /*verilator public_flat_rd*/;
  logic [63:0] pe_cyc  /*verilator public_flat_rd*/;
  logic [63:0] active_cyc  /*verilator public_flat_rd*/;

  always_ff @(posedge clk) begin
    if (!rst_n) begin
      for (int i = 0; i < imap_pkg::NKINDS; i++) kind_cyc[i] = 64'd0;
      for (int i = 0; i < 256; i++) op_cnt[i] = 64'd0;
      for (int i = 0; i < PHASES; i++) phase_cyc[i] = 64'd0;
      pe_cyc = 64'd0;
      active_cyc = 64'd0;
    end else begin
      if (ev_cycle) begin
        kind_cyc[ev_kind] = kind_cyc[ev_kind] + 64'd1;
        if (ev_phase < 16'(PHASES)) phase_cyc[ev_phase[$clog2(PHASES)-1:0]] =
            phase_cyc[ev_phase[$clog2(PHASES)-1:0]] + 64'd1;
        if (ev_pe) begin
          pe_cyc = pe_cyc + 64'd1;
          active_cyc = active_cyc + 64'(ev_active);
        end
      end
      if (ev_retire) op_cnt[ev_op] = op_cnt[ev_op] + 64'd1;
    end
  end

endmodule
