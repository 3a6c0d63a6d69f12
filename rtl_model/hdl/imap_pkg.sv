// IMAP-VISION array, register-transfer design: shared definitions.
//
// Written from docs/isa.md (sections 2-4): the opcode map, the operand
// formats, the cost classes and the control word the CP broadcasts to the
// PEs. Nothing here is taken from the instruction-set model's code.
package imap_pkg;

  // ---- ISA opcodes (docs/isa.md section 4) --------------------------------
  localparam logic [7:0] OP_NOP = 8'h00, OP_HALT = 8'h01, OP_PHASE = 8'h02;
  localparam logic [7:0] OP_CLI = 8'h08, OP_CMOV = 8'h09, OP_CADD = 8'h0A, OP_CADDI = 8'h0B;
  localparam logic [7:0] OP_CSUB = 8'h0C, OP_CSUBI = 8'h0D, OP_CAND = 8'h0E, OP_CANDI = 8'h0F;
  localparam logic [7:0] OP_COR = 8'h10, OP_CORI = 8'h11, OP_CXOR = 8'h12, OP_CXORI = 8'h13;
  localparam logic [7:0] OP_CSHLI = 8'h14, OP_CSHRI = 8'h15, OP_CSRAI = 8'h16;
  localparam logic [7:0] OP_CLD = 8'h17, OP_CST = 8'h18;
  localparam logic [7:0] OP_JMP = 8'h20, OP_BEQ = 8'h21, OP_BNE = 8'h22, OP_BLT = 8'h23;
  localparam logic [7:0] OP_BGE = 8'h24, OP_BZ = 8'h25, OP_BNZ = 8'h26, OP_LOOP = 8'h27;
  localparam logic [7:0] OP_CALL = 8'h28, OP_RET = 8'h29;
  localparam logic [7:0] OP_ADD = 8'h40, OP_ADC = 8'h41, OP_SUB = 8'h42, OP_SBC = 8'h43;
  localparam logic [7:0] OP_AND = 8'h44, OP_OR = 8'h45, OP_XOR = 8'h46, OP_MIN = 8'h47;
  localparam logic [7:0] OP_MAX = 8'h48;
  localparam logic [7:0] OP_ADDI = 8'h50, OP_ADCI = 8'h51, OP_SUBI = 8'h52, OP_SBCI = 8'h53;
  localparam logic [7:0] OP_ANDI = 8'h54, OP_ORI = 8'h55, OP_XORI = 8'h56, OP_MINI = 8'h57;
  localparam logic [7:0] OP_MAXI = 8'h58;
  localparam logic [7:0] OP_MOV = 8'h60, OP_LI = 8'h61, OP_LC = 8'h62, OP_LCB = 8'h63;
  localparam logic [7:0] OP_PIDX = 8'h64, OP_SETC = 8'h65, OP_SETT = 8'h66, OP_CSEL = 8'h67;
  localparam logic [7:0] OP_TSEL = 8'h68;
  localparam logic [7:0] OP_SHLI = 8'h70, OP_SHRI = 8'h71, OP_ROLC = 8'h72, OP_RORC = 8'h73;
  localparam logic [7:0] OP_SHLV = 8'h74, OP_SHRV = 8'h75;
  localparam logic [7:0] OP_CEQ = 8'h80, OP_CNE = 8'h81, OP_CLTU = 8'h82, OP_CLEU = 8'h83;
  localparam logic [7:0] OP_CGTU = 8'h84, OP_CGEU = 8'h85;
  localparam logic [7:0] OP_CEQI = 8'h88, OP_CNEI = 8'h89, OP_CLTUI = 8'h8A, OP_CLEUI = 8'h8B;
  localparam logic [7:0] OP_CGTUI = 8'h8C, OP_CGEUI = 8'h8D, OP_TC = 8'h8E, OP_TNOT = 8'h8F;
  localparam logic [7:0] OP_LD = 8'h90, OP_ST = 8'h91, OP_LDX = 8'h92, OP_STX = 8'h93;
  localparam logic [7:0] OP_XLD = 8'h94, OP_XST = 8'h95;
  localparam logic [7:0] OP_RXL = 8'hA0, OP_RXR = 8'hA1;
  localparam logic [7:0] OP_MIF = 8'hB0, OP_MELSE = 8'hB1, OP_MEND = 8'hB2, OP_MALL = 8'hB3;
  localparam logic [7:0] OP_RANY = 8'hB4, OP_RALL = 8'hB5;
  localparam logic [7:0] OP_VIN = 8'hC0, OP_VOUT = 8'hC1;

  // ---- operand formats (docs/isa.md section 3) -----------------------------
  typedef enum logic [4:0] {
    FMT_BAD, FMT_NONE, FMT_RRR, FMT_RRI8, FMT_RR, FMT_RI8, FMT_RSH, FMT_CMP, FMT_CMPI,
    FMT_R, FMT_RC, FMT_RCK, FMT_RK, FMT_LD, FMT_LDX, FMT_XFER, FMT_RING, FMT_STAT, FMT_CI,
    FMT_CC, FMT_CCC, FMT_CCI, FMT_CSH, FMT_CMEM, FMT_J, FMT_BCC, FMT_B1, FMT_VIDEO, FMT_PHASE
  } fmt_t;

  // ---- sequencer kinds: one per cost class (docs/isa.md section 2.2) -------
  typedef enum logic [3:0] {
    K_CP, K_ALU, K_MINMAX, K_SHIFT, K_MEM, K_MEMX, K_RING, K_MASK, K_STATUS, K_VIDEO,
    K_XFER, K_PHASE
  } kind_t;
  localparam int NKINDS = 12;

  // ---- PE ALU functions ---------------------------------------------------
  typedef enum logic [4:0] {
    F_NONE, F_ADD, F_ADC, F_SUB, F_SBC, F_AND, F_OR, F_XOR, F_MIN, F_MAX, F_PASSA, F_PASSB,
    F_PIDX, F_SETC, F_SETT, F_CSEL, F_TSEL, F_ROLC, F_RORC, F_SHL, F_SHR, F_CMP, F_LD, F_LDX,
    F_ST, F_STX, F_RING
  } fn_t;

  // comparator functions (F_CMP): T source
  typedef enum logic [2:0] {
    CMP_EQ, CMP_NE, CMP_LT, CMP_LE, CMP_GT, CMP_GE, CMP_C, CMP_NOTT
  } cmp_t;

  // mask commands on the mask bus
  typedef enum logic [2:0] {MK_NONE, MK_IF, MK_ELSE, MK_END, MK_ALL} mask_t;

  // row operations of the line / transfer bus
  typedef enum logic [1:0] {ROW_NONE, ROW_WRITE, ROW_READ} row_t;

  // preload at the edge where the instruction in decode enters execute
  typedef enum logic [1:0] {PRE_NONE, PRE_RING, PRE_ADDR, PRE_ROW} pre_t;

  // ---- the control word broadcast to every PE -------------------------------
  // cw: what the PEs do in this cycle (all fields from the CP's execute stage)
  typedef struct packed {
    logic       act;     // the PEs have something to do in this cycle
    logic       clr;     // reset: clear registers and flags, M = 1
    logic       trace;   // report writes on the trace port (simulation only)
    logic       commit;  // last cycle of the instruction: write back
    logic       step;    // shifter pass / ring hop in this cycle
    logic       first;   // first cycle of the instruction (shifter load)
    fn_t        fn;      // ALU / datapath function
    logic       bimm;    // operand b is the broadcast immediate
    logic [5:0] rd;
    logic [5:0] ra;
    logic [5:0] rb;
    logic [7:0] imm;     // broadcast byte (immediate, CP register byte, pidx byte number)
    logic       rd_we;   // write rd (active PEs)
    logic       c_we;    // write C (active PEs)
    logic       t_we;    // write T (active PEs)
    cmp_t       cmp;
    mask_t      mask;    // mask command (all PEs)
    logic       up;      // ring direction: 1 = rxl (data to higher PE indices)
    logic [2:0] sbits;   // shifter bits per pass (cost table shift_bits)
    row_t       row;     // row bus operation in this cycle
    logic [3:0] nrows;   // rows written in this cycle (ROW_WRITE)
    logic       rowm;    // the row write is masked (xld: active PEs only; vin: all PEs)
    pre_t       pre;     // preload for the instruction entering execute at this edge
    logic       pre_nohi;  // ldx / stx without a high-byte register
  } cw_t;

  // cwx: addresses and the preload register selects
  typedef struct packed {
    logic [5:0]  pre_ra;  // preload source register (ring: ra; ldx / stx: low byte)
    logic [5:0]  pre_rb;  // ldx / stx high-byte register
    logic [19:0] addr;    // broadcast local-memory address of this cycle
  } cwx_t;

  // ---- the chip's inputs from the host (docs/rtl.md) -------------------------
  // Host port: the program and the param block, written while rst_n = 0.
  typedef struct packed {
    logic        we;
    logic        sel;   // 0 = instruction memory, 1 = param block
    logic [23:0] addr;
    logic [63:0] data;
  } host_t;

  // Straps: the cost table (docs/isa.md 2.2) and the run-time machine
  // configuration, sampled while rst_n = 0 and held during the run. The
  // testbench top (rtl_model/verif/imap_tb.sv) has one port per field.
  typedef struct packed {
    logic [31:0] c_alu;
    logic [31:0] c_mem;
    logic [31:0] c_indirect_extra;
    logic [31:0] c_ring_hop;
    logic [31:0] c_mask;
    logic [31:0] c_status;
    logic [31:0] c_cp;
    logic [31:0] c_branch_taken;
    logic [31:0] c_video_line;
    logic [31:0] c_xfer_setup;
    logic [31:0] c_ext_bpc;
    logic [31:0] c_ext_beat;
    logic [31:0] c_shift_bits;
    logic [31:0] c_minmax_extra;
    logic [31:0] cfg_prog_len;
    logic [7:0]  cfg_pe_regs;
    logic [8:0]  cfg_mask_depth;
    logic [8:0]  cfg_call_depth;
    logic        cfg_indirect;
    logic        cfg_ext_on;
    logic [63:0] cfg_watchdog;
    logic        cfg_trace;
  } straps_t;

  // ---- faults -------------------------------------------------------------
  typedef enum logic [4:0] {
    FLT_NONE, FLT_ILLEGAL, FLT_PC_END, FLT_WATCHDOG, FLT_MEM, FLT_MEMX, FLT_PARAM,
    FLT_MASK_OVF, FLT_MASK_UNF, FLT_CALL_OVF, FLT_CALL_UNF, FLT_EXT_NONE, FLT_XFER_LEN,
    FLT_XFER_LOCAL, FLT_XFER_EXT, FLT_VID_PORT, FLT_VID_LINE, FLT_VID_MEM
  } fault_t;

  // ---- decode tables ------------------------------------------------------
  function automatic fmt_t op_format(logic [7:0] op);
    case (op)
      imap_pkg::OP_NOP, imap_pkg::OP_HALT: op_format = imap_pkg::FMT_NONE;
      imap_pkg::OP_PHASE: op_format = imap_pkg::FMT_PHASE;
      imap_pkg::OP_CLI: op_format = imap_pkg::FMT_CI;
      imap_pkg::OP_CMOV: op_format = imap_pkg::FMT_CC;
      imap_pkg::OP_CADD, imap_pkg::OP_CSUB, imap_pkg::OP_CAND, imap_pkg::OP_COR, imap_pkg::OP_CXOR: op_format = imap_pkg::FMT_CCC;
      imap_pkg::OP_CADDI, imap_pkg::OP_CSUBI, imap_pkg::OP_CANDI, imap_pkg::OP_CORI, imap_pkg::OP_CXORI: op_format = imap_pkg::FMT_CCI;
      imap_pkg::OP_CSHLI, imap_pkg::OP_CSHRI, imap_pkg::OP_CSRAI: op_format = imap_pkg::FMT_CSH;
      imap_pkg::OP_CLD, imap_pkg::OP_CST: op_format = imap_pkg::FMT_CMEM;
      imap_pkg::OP_JMP, imap_pkg::OP_CALL: op_format = imap_pkg::FMT_J;
      imap_pkg::OP_BEQ, imap_pkg::OP_BNE, imap_pkg::OP_BLT, imap_pkg::OP_BGE: op_format = imap_pkg::FMT_BCC;
      imap_pkg::OP_BZ, imap_pkg::OP_BNZ, imap_pkg::OP_LOOP: op_format = imap_pkg::FMT_B1;
      imap_pkg::OP_RET: op_format = imap_pkg::FMT_NONE;
      imap_pkg::OP_ADD, imap_pkg::OP_ADC, imap_pkg::OP_SUB, imap_pkg::OP_SBC, imap_pkg::OP_AND, imap_pkg::OP_OR, imap_pkg::OP_XOR, imap_pkg::OP_MIN, imap_pkg::OP_MAX: op_format = imap_pkg::FMT_RRR;
      imap_pkg::OP_ADDI, imap_pkg::OP_ADCI, imap_pkg::OP_SUBI, imap_pkg::OP_SBCI, imap_pkg::OP_ANDI, imap_pkg::OP_ORI, imap_pkg::OP_XORI, imap_pkg::OP_MINI, imap_pkg::OP_MAXI:
        op_format = imap_pkg::FMT_RRI8;
      imap_pkg::OP_MOV: op_format = imap_pkg::FMT_RR;
      imap_pkg::OP_LI: op_format = imap_pkg::FMT_RI8;
      imap_pkg::OP_LC: op_format = imap_pkg::FMT_RC;
      imap_pkg::OP_LCB: op_format = imap_pkg::FMT_RCK;
      imap_pkg::OP_PIDX: op_format = imap_pkg::FMT_RK;
      imap_pkg::OP_SETC, imap_pkg::OP_SETT: op_format = imap_pkg::FMT_R;
      imap_pkg::OP_CSEL, imap_pkg::OP_TSEL: op_format = imap_pkg::FMT_RRR;
      imap_pkg::OP_SHLI, imap_pkg::OP_SHRI: op_format = imap_pkg::FMT_RSH;
      imap_pkg::OP_ROLC, imap_pkg::OP_RORC: op_format = imap_pkg::FMT_RR;
      imap_pkg::OP_SHLV, imap_pkg::OP_SHRV: op_format = imap_pkg::FMT_RRR;
      imap_pkg::OP_CEQ, imap_pkg::OP_CNE, imap_pkg::OP_CLTU, imap_pkg::OP_CLEU, imap_pkg::OP_CGTU, imap_pkg::OP_CGEU: op_format = imap_pkg::FMT_CMP;
      imap_pkg::OP_CEQI, imap_pkg::OP_CNEI, imap_pkg::OP_CLTUI, imap_pkg::OP_CLEUI, imap_pkg::OP_CGTUI, imap_pkg::OP_CGEUI: op_format = imap_pkg::FMT_CMPI;
      imap_pkg::OP_TC, imap_pkg::OP_TNOT: op_format = imap_pkg::FMT_NONE;
      imap_pkg::OP_LD, imap_pkg::OP_ST: op_format = imap_pkg::FMT_LD;
      imap_pkg::OP_LDX, imap_pkg::OP_STX: op_format = imap_pkg::FMT_LDX;
      imap_pkg::OP_XLD, imap_pkg::OP_XST: op_format = imap_pkg::FMT_XFER;
      imap_pkg::OP_RXL, imap_pkg::OP_RXR: op_format = imap_pkg::FMT_RING;
      imap_pkg::OP_MIF, imap_pkg::OP_MELSE, imap_pkg::OP_MEND, imap_pkg::OP_MALL: op_format = imap_pkg::FMT_NONE;
      imap_pkg::OP_RANY, imap_pkg::OP_RALL: op_format = imap_pkg::FMT_STAT;
      imap_pkg::OP_VIN, imap_pkg::OP_VOUT: op_format = imap_pkg::FMT_VIDEO;
      default: op_format = imap_pkg::FMT_BAD;
    endcase
  endfunction

  function automatic kind_t op_kind(logic [7:0] op);
    case (op)
      imap_pkg::OP_PHASE: op_kind = imap_pkg::K_PHASE;
      imap_pkg::OP_MIN, imap_pkg::OP_MAX, imap_pkg::OP_MINI, imap_pkg::OP_MAXI: op_kind = imap_pkg::K_MINMAX;
      imap_pkg::OP_SHLI, imap_pkg::OP_SHRI, imap_pkg::OP_SHLV, imap_pkg::OP_SHRV: op_kind = imap_pkg::K_SHIFT;
      imap_pkg::OP_LD, imap_pkg::OP_ST: op_kind = imap_pkg::K_MEM;
      imap_pkg::OP_LDX, imap_pkg::OP_STX: op_kind = imap_pkg::K_MEMX;
      imap_pkg::OP_XLD, imap_pkg::OP_XST: op_kind = imap_pkg::K_XFER;
      imap_pkg::OP_RXL, imap_pkg::OP_RXR: op_kind = imap_pkg::K_RING;
      imap_pkg::OP_MIF, imap_pkg::OP_MELSE, imap_pkg::OP_MEND, imap_pkg::OP_MALL: op_kind = imap_pkg::K_MASK;
      imap_pkg::OP_RANY, imap_pkg::OP_RALL: op_kind = imap_pkg::K_STATUS;
      imap_pkg::OP_VIN, imap_pkg::OP_VOUT: op_kind = imap_pkg::K_VIDEO;
      default:
        if (op >= 8'h40) op_kind = imap_pkg::K_ALU;
        else op_kind = imap_pkg::K_CP;
    endcase
  endfunction

endpackage
