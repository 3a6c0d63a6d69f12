// The CP's retire monitor (testbench): bound into every imap_cp instance by
// rtl_model/verif/imap_tb.sv (`bind imap_cp imap_cp_monitor u_mon (.*)`), it
// watches the CP's commit and fault signals (connected by name) and reports
// through DPI-C (rtl_model/verif/imap_dpi_pkg.sv, rtl_model/verif/dpi.cpp):
//   - the fault that stops the machine, at the edge at which the CP records
//     it in f_code / f_pc_q / f_cyc / f_pe / f_addr;
//   - with the trace strap: at the edge at which an instruction commits, the
//     param-block word a cst writes, then the retire record.
// All inputs are sampled at that edge before the CP's registers take their
// new values, so the record is the one of the committing instruction
// (index = instret before the increment, cycles as the CP counts them).
module imap_cp_monitor (
    input logic clk,
    input logic rst_n,
    input imap_pkg::straps_t straps,
    input logic run_q,
    input logic x_v,
    input logic x_first,
    input imap_pkg::fault_t x_flt,
    input logic [24:0] x_pc,
    input logic [31:0] x_fpe,
    input logic [63:0] x_fad,
    input logic [63:0] mcycle,
    input logic x_commit,
    input logic [63:0] instret,
    input logic [63:0] x_ir,
    input logic [7:0] x_op,
    input logic [31:0] x_addr,
    input logic [31:0] creg[16],
    input logic [63:0] x_cyc0,
    input logic x_zn,
    input logic [15:0] phase_q,
    input logic x_cwe,
    input logic [3:0] x_cidx,
    input logic [31:0] x_cres,
    input logic [8:0] msp_next,
    input logic [8:0] csp_next,
    input logic [16:0] ev_active
);
  import imap_dpi_pkg::*;

  always_ff @(posedge clk)
    if (rst_n) begin
      if (x_v && x_first && x_flt != imap_pkg::FLT_NONE && run_q)
        imap_rtl_fault(int'(x_flt), int'(x_pc), mcycle, int'(x_fpe), x_fad);
      if (x_commit && straps.cfg_trace) begin
        if (x_op == imap_pkg::OP_CST) imap_rtl_param_write(int'(x_addr[7:0]), int'(creg[x_ir[11:8]]));
        imap_rtl_retire(
            instret, int'(x_pc), x_ir, x_cyc0, x_zn ? mcycle : mcycle + 64'd1,
            {16'h0, (x_op == imap_pkg::OP_PHASE) ? x_ir[47:32] : phase_q}, x_cwe ? int'(x_cidx) : -1,
            int'(x_cres), int'(msp_next), int'(csp_next),
            {15'h0, ev_active}, x_op == imap_pkg::OP_HALT);
      end
    end

endmodule
