; IMAP-VISION DP stereo firmware (SPEC Part A on the array; docs/firmware.md).
;
; The host plans each parameter set (firmware/src/plan.cpp) and assembles a
; generated prelude (the constants and the PLAN_* macros: per-column passes
; of the forward pass, spills, reloads, backtrack columns, per-segment
; re-layout) that includes this file, and writes the batch table into the
; param block:
;   param[0]          number of batches
;   param[1 + 4b ..]  first ROI line, lines, first output line (batch-
;                     relative), output lines of batch b
; Input images arrive on video ports 0 (left) and 1 (right); the disparity
; map (ROI-sized) leaves on video output port 0.
.include "dp_setup.inc"
.include "dp_init.inc"
.include "dp_forward.inc"
.include "dp_back.inc"
.include "relayout.inc"

.equ BATCH_IDX 255                  ; param word holding the current batch

        FWD_BODIES
        jmp     main
        BT_COLUMN
main:
        cli     c0, #0
        cst     c0, [#BATCH_IDX]
batch:
        cld     c0, [#BATCH_IDX]
        cshli   c1, c0, #2
        cld     c8, [c1 + 1]                ; first ROI line of the batch
        cld     c9, [c1 + 2]                ; lines in the batch
        DP_SETUP
        PLAN_IN
        DP_EXCHANGE
        DP_INIT
        DP_FORWARD
        DP_CLEARMAP
        DP_BACKTRACK
        DP_MERGE
        cld     c0, [#BATCH_IDX]
        cshli   c1, c0, #2
        cld     c8, [c1 + 1]
        cld     c9, [c1 + 2]
        cld     c10, [c1 + 3]               ; first output line (batch-relative)
        cld     c11, [c1 + 4]               ; output lines
        PLAN_OUT
        cld     c0, [#BATCH_IDX]
        caddi   c0, c0, #1
        cst     c0, [#BATCH_IDX]
        cld     c1, [#0]
        blt     c0, c1, batch
        halt
