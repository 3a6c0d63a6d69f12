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
.include "census.inc"

.equ BATCH_IDX 255                  ; param word holding the current batch

        FWD_BODIES
        jmp     main
        BT_COLUMN
main:
.if TINY
; 2 to 5 PEs with the vote: one line per batch; line b's forward pass, then
; the backtrack of line b-1 with the pointer tables of lines b-2, b-1, b
; (three rotating slots in the external memory).
.equ TLINE 249
.equ TS0 248                        ; slot of line b
.equ TS1 247                        ; slot of line b-1
.equ TS2 246                        ; slot of line b-2
        cli     c0, #0
        cst     c0, [#TLINE]
        cst     c0, [#TS0]
        cli     c0, #TTABLE
        cst     c0, [#TS1]
        cli     c0, #(2 * TTABLE)
        cst     c0, [#TS2]
tloop:
        cld     c0, [#TLINE]
        cld     c1, [#0]
        bge     c0, c1, tback
        cmov    c8, c0
        cli     c9, #1
        DP_SETUP
        PLAN_IN
        DP_EXCHANGE
        AGG_EXTEND
        BT_BOUNDS
        DP_INIT
        cld     c0, [#TS0]
        cst     c0, [#TSLOT_CUR]
        DP_FORWARD
tback:
        cld     c0, [#TLINE]
        bz      c0, tnext
        cld     c1, [#TS1]
        cst     c1, [#TSLOT_OWN]
        cld     c1, [#TS2]
        cst     c1, [#TSLOT_ABOVE]
        cld     c1, [#TS0]
        cst     c1, [#TSLOT_BELOW]
        ; line b-1 votes iff 1 <= b-1 <= HROI-2
        cli     c2, #0
.if VOTE && HROI >= 3
        csubi   c1, c0, #1
        bz      c1, tvset
        cli     c3, #(HROI - 1)
        bge     c1, c3, tvset
        cli     c2, #1
tvset:
.endif
        cst     c2, [#TVOTE]
        DP_CLEARMAP
        DP_BACKTRACK
        DP_MERGE
        cld     c0, [#TLINE]
        csubi   c8, c0, #1
        cli     c9, #1
        cli     c10, #0
        cli     c11, #1
        PLAN_OUT
tnext:
        cld     c0, [#TS2]                  ; the oldest slot is reused for line b+1
        cld     c1, [#TS1]
        cld     c2, [#TS0]
        cst     c1, [#TS2]
        cst     c2, [#TS1]
        cst     c0, [#TS0]
        cld     c0, [#TLINE]
        caddi   c0, c0, #1
        cst     c0, [#TLINE]
        cld     c1, [#0]
        bge     c1, c0, tloop               ; b <= H
        halt
.else
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
        AGG_EXTEND
        BT_BOUNDS
        DP_INIT
        DP_FORWARD
        DP_MEET
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
.endif
