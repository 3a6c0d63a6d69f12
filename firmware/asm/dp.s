; IMAP-VISION DP stereo firmware (SPEC Part A on the array; docs/firmware.md).
;
; The host plans each parameter set (firmware/src/plan.cpp) and assembles a
; generated prelude (the constants and the PLAN_* macros: per-column passes
; of the forward pass, spills, reloads, backtrack columns, per-segment
; re-layout) that includes this file, and writes the number of batches
; into param[0]. The batches follow from three constants (no table, so no
; limit on their number): batch outputs ROI lines o .. o + BSTRIDE - 1
; (o = 0, BSTRIDE, ...; the last one ends at HROI), and with BOVERLAP it
; also holds that many lines above and below them (the halo: the vote's
; neighbours, the vertical window's and the census's lines; their own
; results are never output).
; Input images arrive on video ports 0 (left) and 1 (right); the disparity
; map (ROI-sized) leaves on video output port 0.
.include "dp_setup.inc"
.include "dp_init.inc"
.include "dp_forward.inc"
.include "dp_back.inc"
.include "relayout.inc"
.include "census.inc"

.equ BATCH_IDX 255                  ; param word holding o, the batch's first output line

; c8 = first ROI line of the batch at o, c9 = its lines (c0 = o; uses c1).
.macro BATCH_LINES
        cld     c0, [#BATCH_IDX]
        caddi   c9, c0, #BSTRIDE
        cli     c1, #HROI
        blt     c9, c1, bla\@
        cmov    c9, c1                      ; oe = min(HROI, o + BSTRIDE)
bla\@:
        cmov    c8, c0
.if BOVERLAP
        bge     c9, c1, blb\@
        caddi   c9, c9, #BOVERLAP           ; last = min(HROI, oe + BOVERLAP)
.if BOVERLAP > 1
        blt     c9, c1, blb\@
        cmov    c9, c1
.endif
blb\@:
.if BOVERLAP > 1
        cli     c8, #0
        cli     c1, #BOVERLAP
        blt     c0, c1, bld\@
        csubi   c8, c0, #BOVERLAP           ; first = max(0, o - BOVERLAP)
bld\@:
        cli     c1, #HROI
.else
        bz      c0, blc\@
        csubi   c8, c0, #1                  ; first = max(0, o - 1)
blc\@:
.endif
.endif
        csub    c9, c9, c8
.endm

; ... and c10 = first output line (batch-relative), c11 = output lines.
.macro BATCH_OUT
        BATCH_LINES
        csub    c10, c0, c8
        caddi   c11, c0, #BSTRIDE
        blt     c11, c1, bod\@
        cmov    c11, c1
bod\@:
        csub    c11, c11, c0
.endm

        FWD_BODIES
        jmp     main
        BT_COLUMN
.if BSTEP
        BT_WALK
.endif
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
        BATCH_LINES
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
        BATCH_OUT
        PLAN_OUT
        cld     c0, [#BATCH_IDX]
        caddi   c0, c0, #BSTRIDE
        cst     c0, [#BATCH_IDX]
        cli     c1, #HROI
        blt     c0, c1, batch
        halt
.endif
