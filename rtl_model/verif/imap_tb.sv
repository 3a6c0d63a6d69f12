`include "imap_mutants.svh"
// The testbench top (the Verilator top module of every verilated
// configuration): the chip (rtl_model/hdl/imap_top.sv, instance u_chip) and
// the board model next to it (imap_board.sv, instance u_board: external
// memory, camera / display). Its ports are the ones the SystemC bench binds
// (model_impl.hpp): clock, reset, the host port, the straps and done (one
// port per field of imap_pkg::host_t / straps_t, packed below). The
// retire monitor (imap_cp_monitor.sv) is bound into the chip's CP below; the
// design tree does not reference this folder.
`include "imap_ports.svh"
module imap_tb
#(
`include "imap_params.svh"
) (
    `IMAP_CLOCK_PORTS
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
    output logic done
);

  // the chip's board interface
  logic xe_pf, xe_wr, vid_open, vid_out, vid_put;
  logic [31:0] xe_prow, xe_wrow, vid_oy, vid_ox, vid_py, vid_px;
  logic [3:0] xe_n;
  logic [P-1:0] xe_pm;
  logic [0:0] vid_oport, vid_pport;
  logic [1:0] vid_status;
  logic [63:0] vid_ready;
  logic [P*XROWS*8-1:0] rbus;
  logic [P*XROWS*8-1:0] rrow;

  // the host port and the straps, packed as the chip takes them (the
  // fields of imap_pkg::host_t / straps_t, in their order)
  imap_pkg::host_t host;
  imap_pkg::straps_t straps;
  assign host = '{host_we, host_sel, host_addr, host_data};
  assign straps = '{
          c_alu, c_mem, c_indirect_extra, c_ring_hop, c_mask, c_status, c_cp, c_branch_taken,
          c_video_line, c_xfer_setup, c_ext_bpc, c_ext_beat, c_shift_bits, c_minmax_extra,
          cfg_prog_len, cfg_pe_regs, cfg_mask_depth, cfg_call_depth, cfg_indirect, cfg_ext_on,
          cfg_watchdog, cfg_trace
      };

  imap_top #(`IMAP_PARAMS_PASS) u_chip (.*);

  imap_board #(
      .P(P),
      .EXT_BYTES(EXT_BYTES),
      .XROWS(XROWS)
  ) u_board (.*);

  // the retire record, the param-block writes and the fault report
  bind imap_cp imap_cp_monitor u_mon (.*);

endmodule
