; firmware/asm/dp.s with its .include files inlined and the -D constants of
; `imapsim run --size 64x32 --D 16` as .equ lines (fuzzing seed).
.equ MODE 1
.equ N 64
.equ D 16
.equ S 28
.equ DS -1
.equ KMAX 35
.equ DQ 4
.equ KM 8
.equ KB 1
.equ GB 64
.equ WO 100
.equ WD 100
.equ IMGR 0
.equ IMGL 36
.equ COST0 88
.equ COST1 105
.equ COST2 122
.equ PBUF 139
.equ VBUF 143
.equ MAP 0
.equ K_BASE 147
.equ FRAME 0
.equ VOTE 1
.equ P 256
.equ HROI 32
.equ X0 0
.equ Y0 0
.equ NSEG 1
.equ INL 168
.equ INR 200
.equ OUT 88
.equ SPLIT_IN 0
; IMAP-VISION DP stereo firmware (SPEC Part A on the array; docs/firmware.md).
;
; The host assembles this file once per parameter set (-D constants: the
; algorithm's parameters, the ROI, the PE count and the memory plan) and
; writes the batch table into the param block:
;   param[0]          number of batches
;   param[1 + 4b ..]  first ROI line, lines, first output line (batch-
;                     relative), output lines of batch b
; Input images arrive on video ports 0 (left) and 1 (right); the disparity
; map (ROI-sized) leaves on video output port 0.
; Start column of the DP (docs/firmware.md, section 1), written to the cost
; planes COST0/COST1/COST2 at levels 0..D-1, and the pad level D = INF.
;   single:           E(0, j) = j * Wo (the virtual column -1)
;   bidir, right PEs: site s;   fixed ds: (j - ds) * Wo for j >= ds, INF below;
;                     free: 0;  INF where s + j > N - 1
;   bidir, left PEs:  site s-1, mirrored level j' = D-1-j;
;                     fixed ds: (ds - j) * Wo for j <= ds, INF above;
;                     free: 0;  INF where s - 1 + j > N - 1
; Left PEs are the even PEs in bidir mode. All values are assembly-time
; constants; the per-PE choice is one tsel per byte.
; Constants: MODE (0 single, 1 bidir), N, D, S, DS (-1 = free), WO, COST0-COST2.

.equ INF 0x800000

.macro STORE24 V, J
        li      r10, #((\V) & 255)
        li      r11, #(((\V) >> 8) & 255)
        li      r12, #(((\V) >> 16) & 255)
        st      r10, [#(COST0 + (\J))]
        st      r11, [#(COST1 + (\J))]
        st      r12, [#(COST2 + (\J))]
.endm

.macro DP_INIT
.phase init
.if MODE == 0
.set IJ 0
.rept D
        STORE24 (IJ * WO), IJ
.set IJ IJ + 1
.endr
.else
        pidx    r13, #0
        andi    r13, r13, #1
        ceqi    r13, #0                     ; T = left-wavefront PE
.set IJ 0
.rept D
; right PE value VR at level IJ
.if S + IJ > N - 1
.set VR INF
.elif DS < 0
.set VR 0
.elif IJ >= DS
.set VR (IJ - DS) * WO
.else
.set VR INF
.endif
; left PE value VL at mirrored level IJ (true level D-1-IJ)
.set LJ D - 1 - IJ
.if S - 1 + LJ > N - 1
.set VL INF
.elif DS < 0
.set VL 0
.elif LJ <= DS
.set VL (DS - LJ) * WO
.else
.set VL INF
.endif
        li      r10, #(VR & 255)
        li      r11, #((VR >> 8) & 255)
        li      r12, #((VR >> 16) & 255)
        li      r4, #(VL & 255)
        li      r5, #((VL >> 8) & 255)
        li      r6, #((VL >> 16) & 255)
        tsel    r10, r4, r10
        tsel    r11, r5, r11
        tsel    r12, r6, r12
        st      r10, [#(COST0 + IJ)]
        st      r11, [#(COST1 + IJ)]
        st      r12, [#(COST2 + IJ)]
.set IJ IJ + 1
.endr
.endif
        STORE24 INF, D
.endm
; Forward pass of the DP on every PE at once (docs/firmware.md, sections 1-2).
;
; Every PE runs the right-wavefront recurrence on its own line buffers
;   R'[k] at IMGR + k, L'[m] at IMGL + m
; (the left wavefront's PEs hold mirrored data, so the same code is exact for
; both). Costs are 24-bit in three byte planes COST0/COST1/COST2 (level j at +j, the
; pad level D holds INF). Column 0 (the start column) must be in the planes;
; columns 1..KMAX are computed and their 2-bit pointers (M=0, D=1, O=2),
; packed four to a byte with the lowest level in the top bits, go to the
; external memory, column k at (k-1)*DQ.
;
; Constants (assembly time): D, KMAX, KM, KB, GB, WO, WD, IMGR, IMGL, COST0, COST1,
; COST2, PBUF, DQ.
; Registers: r0 a=R'[k]; r1-r3 P / M / best; r4-r6 Q; r7-r9 run (O chain);
; r10-r13 temporaries; r14 pointer; r15 packed pointers.
; CP: c0 k, c1 j, c2 k+j, c3 external address, c4 group count, c5 columns
; left, c6 DQ, c7 pointer byte address.

; MULC src, lo, hi, t1, t2, K
;   (hi:lo) = src * K for an assembly-time constant 0 <= K < 65536, by shifts
;   and adds (the PEs have no multiplier). src is kept; t1, t2 are clobbered.
;   The caller guarantees src * K < 65536.
.macro MULC src, lo, hi, t1, t2, K
.set MC_FIRST 1
.set MC_B 0
.rept 16
.if ((\K) >> MC_B) & 1
.if MC_B == 0
.if MC_FIRST
        mov     \lo, \src
        li      \hi, #0
.else
        add     \lo, \lo, \src
        adci    \hi, \hi, #0
.endif
.elif MC_B < 8
.if MC_FIRST
        shli    \lo, \src, #MC_B
        shri    \hi, \src, #(8 - MC_B)
.else
        shli    \t1, \src, #MC_B
        shri    \t2, \src, #(8 - MC_B)
        add     \lo, \lo, \t1
        adc     \hi, \hi, \t2
.endif
.else
.if MC_FIRST
        li      \lo, #0
        shli    \hi, \src, #(MC_B - 8)
.else
        shli    \t1, \src, #(MC_B - 8)
        add     \hi, \hi, \t1
.endif
.endif
.set MC_FIRST 0
.endif
.set MC_B MC_B + 1
.endr
.if MC_FIRST
        li      \lo, #0
        li      \hi, #0
.endif
.endm

.macro DP_NODE
        ld      r13, [c2 + IMGL]            ; b = L'[k+j]
        max     r4, r0, r13
        min     r5, r0, r13
        sub     r4, r4, r5                  ; |a - b|
        li      r6, #GB
        sub     r6, r6, r5                  ; gb - min(a,b), C = borrow
        li      r13, #0
        csel    r6, r13, r6                 ; max(0, gb - min(a,b))
        MULC    r4, r10, r11, r12, r13, KM  ; km * |a - b|
        MULC    r6, r4, r5, r12, r13, KB    ; kb * max(0, gb - min)
        add     r10, r10, r4
        adc     r11, r11, r5                ; Wm (16 bit)
        add     r1, r1, r10
        adc     r2, r2, r11
        adci    r3, r3, #0                  ; M = E(k-1, j) + Wm
        ld      r4, [c1 + (COST0 + 1)]
        ld      r5, [c1 + (COST1 + 1)]
        ld      r6, [c1 + (COST2 + 1)]         ; Q = E(k-1, j+1)
        addi    r10, r4, #(WD & 255)
        adci    r11, r5, #((WD >> 8) & 255)
        adci    r12, r6, #((WD >> 16) & 255) ; D = Q + Wd
        sub     r13, r10, r1
        sbc     r13, r11, r2
        sbc     r13, r12, r3                ; C = D < M (strictly)
        setc    r14                         ; pointer: M = 0, D = 1
        csel    r1, r10, r1
        csel    r2, r11, r2
        csel    r3, r12, r3                 ; best of M, D
        addi    r10, r7, #(WO & 255)
        adci    r11, r8, #((WO >> 8) & 255)
        adci    r12, r9, #((WO >> 16) & 255) ; O = E(k, j-1) + Wo
        sub     r13, r10, r1
        sbc     r13, r11, r2
        sbc     r13, r12, r3                ; C = O < best (strictly)
        csel    r7, r10, r1
        csel    r8, r11, r2
        csel    r9, r12, r3                 ; E(k, j)
        li      r13, #2
        csel    r14, r13, r14               ; pointer: O = 2
        st      r7, [c1 + COST0]
        st      r8, [c1 + COST1]
        st      r9, [c1 + COST2]
        shli    r15, r15, #2
        or      r15, r15, r14
        mov     r1, r4
        mov     r2, r5
        mov     r3, r6                      ; next level's E(k-1, j)
        caddi   c1, c1, #1
        caddi   c2, c2, #1
.endm

.macro DP_FORWARD
.phase forward
        cli     c0, #1
        cli     c3, #0
        cli     c5, #KMAX
        cli     c6, #DQ
dpf_col\@:
        ld      r0, [c0 + IMGR]
        li      r7, #0
        li      r8, #0
        li      r9, #0x80                   ; E(k, -1) = INF: no O into level 0
        ld      r1, [#COST0]
        ld      r2, [#COST1]
        ld      r3, [#COST2]
        cli     c1, #0
        cmov    c2, c0
        cli     c7, #PBUF
.if (D / 4) > 0
        cli     c4, #(D / 4)
dpf_grp\@:
        DP_NODE
        DP_NODE
        DP_NODE
        DP_NODE
        st      r15, [c7]
        caddi   c7, c7, #1
        loop    c4, dpf_grp\@
.endif
.if (D % 4) > 0
.rept D % 4
        DP_NODE
.endr
        shli    r15, r15, #(2 * (4 - D % 4))
        st      r15, [c7]
.endif
        xst     [#PBUF], ext[c3], c6
        cadd    c3, c3, c6
        caddi   c0, c0, #1
        loop    c5, dpf_col\@
.endm
; Per-PE set-up, vote + backtrack, and merge of the DP (docs/firmware.md,
; section 4).
;
; Coordinates are the forward pass's (column k, level j); both kinds of PE
; walk the same way: M -> (k-1, j), D -> (k-1, j+1), O -> (k, j-1).
;   right / single PE: starts at (KST, 0); an M event is the current state
;   left PE:           starts at (S, D-1); an M event is the arrival state
; The output position of a state is Z = ALPHA*site + BETA*level (cyclopean:
; 2, 1 then >> 1; left frame: 1, 1; right frame: 1, 0), kept per PE in 16 bits
; and updated by the step's delta (a per-PE table of three 16-bit values).
;
; Constants: MODE, N, D, S, DS, KMAX, DQ, FRAME (0 cyc, 1 left, 2 right),
; VOTE, HROI (ROI lines), PBUF, VBUF, MAP, and the per-PE constant block at
; K_BASE. CP inputs of DP_SETUP: c8 = ROI line of this batch's first line,
; c9 = lines in this batch.

.if FRAME == 0
.equ ALPHA 2
.equ BETA 1
.equ ZSH 1
.elif FRAME == 1
.equ ALPHA 1
.equ BETA 1
.equ ZSH 0
.else
.equ ALPHA 1
.equ BETA 0
.equ ZSH 0
.endif
.if MODE == 0
.equ VSTEP 1          ; ring distance to the same wavefront of the next line
.else
.equ VSTEP 2
.endif

; per-PE constant block
.equ K_VALID  K_BASE + 0    ; 1 if this PE holds a line of the batch
.equ K_VOTE   K_BASE + 1    ; 1 if the line votes (both neighbours in the ROI)
.equ K_LEFT   K_BASE + 2    ; 1 on left-wavefront PEs
.equ K_KST    K_BASE + 3    ; start column (16 bit)
.equ K_Z      K_BASE + 5    ; Z of the start state (16 bit)
.equ K_EVOFF  K_BASE + 7    ; Z offset of an M event (16 bit)
.equ K_LMUL   K_BASE + 9    ; level of an event = (j ^ LMUL) + LOFF
.equ K_LOFF   K_BASE + 10
.equ K_DELTA  K_BASE + 11   ; Z deltas of M, D, O (3 x 16 bit)
.equ K_SIZE   17   ; relayout.inc adds 4 bytes after the block

; SETK addr, left_value, right_value: one byte per PE by kind (T = left PE)
.macro SETK A, VL, VR
        li      r10, #((\VL) & 255)
        li      r11, #((\VR) & 255)
        tsel    r10, r10, r11
        st      r10, [#(\A)]
.endm
.macro SETK16 A, VL, VR
        SETK    \A, (\VL), (\VR)
        SETK    (\A) + 1, ((\VL) >> 8), ((\VR) >> 8)
.endm

.macro DP_SETUP
.phase setup
        ; line of this PE within the batch (16 bit: r1:r0)
        pidx    r0, #0
        pidx    r1, #1
.if MODE == 1
        shri    r1, r1, #1
        rorc    r0, r0
.endif
        ; valid = line < c9
        lcb     r2, c9, #0
        lcb     r3, c9, #1
        sub     r4, r0, r2
        sbc     r4, r1, r3
        setc    r5                          ; C = line < lines in batch
        st      r5, [#K_VALID]
        ; ROI line = line + c8; votes iff 1 <= ROI line <= HROI - 2 and valid
        lcb     r2, c8, #0
        lcb     r3, c8, #1
        add     r0, r0, r2
        adc     r1, r1, r3
        li      r6, #0
.if VOTE && HROI >= 3
        subi    r2, r0, #1
        sbci    r3, r1, #0                  ; C = ROI line < 1
        tc
        tnot                                ; T = ROI line >= 1
        sett    r6
        li      r2, #((HROI - 2) & 255)
        li      r3, #(((HROI - 2) >> 8) & 255)
        sub     r2, r2, r0
        sbc     r3, r3, r1                  ; C = HROI - 2 < ROI line
        tc
        tnot
        sett    r7
        and     r6, r6, r7
        and     r6, r6, r5
.endif
        st      r6, [#K_VOTE]
        ; kind: left-wavefront PEs are the even ones in bidir mode
.if MODE == 1
        pidx    r13, #0
        andi    r13, r13, #1
        ceqi    r13, #0                     ; T = left PE
.else
        li      r13, #1
        ceqi    r13, #0                     ; T = 0 everywhere
.endif
        sett    r10
        st      r10, [#K_LEFT]
.if MODE == 1
        SETK16  K_KST, S, (N - 1 - S)
        SETK16  K_Z, (-ALPHA), (ALPHA * (N - 1))
        SETK16  K_EVOFF, ALPHA, 0
        SETK    K_LMUL, 0xFF, 0
        SETK    K_LOFF, D, 0
        SETK16  K_DELTA + 0, ALPHA, (-ALPHA)
        SETK16  K_DELTA + 2, (ALPHA - BETA), (BETA - ALPHA)
        SETK16  K_DELTA + 4, BETA, (-BETA)
.else
        SETK16  K_KST, N, N
        SETK16  K_Z, ALPHA * (N - 1), ALPHA * (N - 1)
        SETK16  K_EVOFF, 0, 0
        SETK    K_LMUL, 0, 0
        SETK    K_LOFF, 0, 0
        SETK16  K_DELTA + 0, (-ALPHA), (-ALPHA)
        SETK16  K_DELTA + 2, (BETA - ALPHA), (BETA - ALPHA)
        SETK16  K_DELTA + 4, (-BETA), (-BETA)
.endif
.endm

; Output line: all occluded.
.macro DP_CLEARMAP
        li      r10, #255
.set MI 0
.rept N
        st      r10, [#(MAP + MI)]
.set MI MI + 1
.endr
.endm

; Vote of the pointer column in PBUF into VBUF (SPEC A.5): per 2-bit field,
; the neighbours' pointer where the lines above and below agree, else own.
; Uses r5-r10 only (the backtrack keeps its state in r0-r4).
.macro DP_VOTE
        ld      r13, [#K_VOTE]
        ceqi    r13, #1                     ; T = this line votes
        cli     c10, #0
        cli     c11, #DQ
dpv_byte\@:
        ld      r5, [c10 + PBUF]            ; own
        rxl     r6, r5, #VSTEP              ; line above
        rxr     r7, r5, #VSTEP              ; line below
        xor     r8, r6, r7
        shri    r9, r8, #1
        or      r8, r8, r9
        andi    r8, r8, #0x55
        shli    r9, r8, #1
        or      r8, r8, r9                  ; 11 where above != below
        and     r9, r5, r8
        xori    r8, r8, #0xFF
        and     r10, r6, r8
        or      r9, r9, r10                 ; voted
        tsel    r5, r9, r5
        st      r5, [c10 + VBUF]
        caddi   c10, c10, #1
        loop    c11, dpv_byte\@
.endm

; Column-synchronous backtrack (section 4). Registers: r0 j, r1:r2 Z,
; r3 still-in-column, r4 pointer, r5-r9 temporaries, r10:r11 event position.
.macro DP_BACKTRACK
.phase backtrack
        li      r0, #0
        ld      r13, [#K_LEFT]
        ceqi    r13, #1
        li      r5, #((D - 1) & 255)
        tsel    r0, r5, r0                  ; j = D-1 on left PEs, 0 otherwise
        ld      r1, [#K_Z]
        ld      r2, [#(K_Z + 1)]
        cli     c12, #KMAX                  ; column
        cli     c13, #((KMAX - 1) * DQ)     ; its external address
        cli     c6, #DQ
dpb_col\@:
.phase vote
        xld     [#PBUF], ext[c13], c6
        DP_VOTE
.phase backtrack
        ; active = valid && KST >= column
        ld      r5, [#K_KST]
        ld      r6, [#(K_KST + 1)]
        lcb     r7, c12, #0
        lcb     r8, c12, #1
        sub     r5, r5, r7
        sbc     r5, r6, r8                  ; C = KST < column
        setc    r3
        xori    r3, r3, #1
        ld      r5, [#K_VALID]
        and     r3, r3, r5
dpb_step\@:
        ceqi    r3, #1
        mif
        ; pointer of (column, j) from the voted column
        shri    r5, r0, #2
        ldx     r6, [r5 + VBUF]
        andi    r7, r0, #3
        shli    r7, r7, #1
        li      r8, #6
        sub     r7, r8, r7
        shrv    r4, r6, r7
        andi    r4, r4, #3
        ; M event: map[(Z + EVOFF) >> ZSH] = (j ^ LMUL) + LOFF
        ceqi    r4, #0
        mif
        ld      r5, [#K_EVOFF]
        ld      r6, [#(K_EVOFF + 1)]
        add     r10, r1, r5
        adc     r11, r2, r6
.if ZSH == 1
        shri    r11, r11, #1
        rorc    r10, r10
.endif
        ld      r5, [#K_LMUL]
        xor     r5, r0, r5
        ld      r6, [#K_LOFF]
        add     r5, r5, r6
        stx     r5, [r10:r11 + MAP]
        mend
        ; Z += delta[pointer]
        shli    r5, r4, #1
        ldx     r6, [r5 + K_DELTA]
        ldx     r7, [r5 + (K_DELTA + 1)]
        add     r1, r1, r6
        adc     r2, r2, r7
        ; level: O -> j-1, D -> j+1; M or D leave the column
        ceqi    r4, #2
        mif
        subi    r0, r0, #1
        melse
        add     r0, r0, r4
        li      r3, #0
        mend
        mend
        ceqi    r3, #1
        rany    c14
        bnz     c14, dpb_step\@
        csubi   c13, c13, #DQ
        csubi   c12, c12, #1
        bnz     c12, dpb_col\@
.if MODE == 1
        ; seed of the right wavefront: M event at (s, ds) or (s, level reached)
        ld      r13, [#K_LEFT]
        ceqi    r13, #0
        mif
        ld      r13, [#K_VALID]
        ceqi    r13, #1
        mif
.if DS >= 0
        li      r5, #DS
        st      r5, [#(MAP + ((ALPHA * S + BETA * DS) >> ZSH))]
.else
        mov     r10, r1
        mov     r11, r2
.if ZSH == 1
        shri    r11, r11, #1
        rorc    r10, r10
.endif
        stx     r0, [r10:r11 + MAP]
.endif
        mend
        mend
.endif
.endm

; Bidir: the left PE's map goes one hop up to the right PE of its line; the
; right wavefront's events win where it wrote (SPEC A.7).
.macro DP_MERGE
.if MODE == 1
.phase merge
        ld      r3, [#K_LEFT]
        cli     c10, #0
        cli     c11, #N
dpm_x\@:
        ld      r0, [c10 + MAP]
        rxl     r1, r0, #1                  ; the left PE's value, on the right PE
        cnei    r0, #255
        tsel    r2, r0, r1                  ; right wavefront wins where it wrote
        ceqi    r3, #1
        tsel    r2, r0, r2                  ; left PEs keep their own line
        st      r2, [c10 + MAP]
        caddi   c10, c10, #1
        loop    c11, dpm_x\@
.endif
.endm
; Video re-layout (docs/firmware.md, section 5).
;
; In:  `vin` puts pixel X0 + g*P + p of an image line on PE p (segment g).
;      The batch's lines are loaded into rows INL + y / INR + y, then P rounds
;      move every pixel to the PEs of its line: in round t every PE sends the
;      pixel whose destination is t PEs up (line ((p + t) mod P) >> LSH),
;      the ring carries it t hops, and the receiver stores it at its own
;      position in R' / L' (docs section 1), if that position is used.
; Out: the reverse: the output PE of line y sends MAP[g*P + ((q + t) mod P)]
;      to PE (q + t) mod P, which stores it in row OUT + y; `vout` writes the
;      rows as lines of the output image.
;
; Constants: P, MODE, N, D, S, KMAX, X0, Y0, IMGR, IMGL, MAP, INL, INR, OUT,
; NSEG (segments of P pixels), K_BASE block (dp_back.inc).
; CP inputs: c8 = ROI line of the batch's first line, c9 = lines in the batch.

.if MODE == 1
.equ LSH 1
.else
.equ LSH 0
.endif
.equ LIMR KMAX              ; R' indices 0..KMAX
.equ LIML KMAX + D          ; L' indices 0..KMAX+D
.equ K_DLT  K_BASE + K_SIZE       ; per-round change of the R'/L' index (16 bit)
.equ K_WRAP K_BASE + K_SIZE + 2   ; change when the source wraps around (16 bit)

; SHIFTUP ra, rb: both registers move c15 PEs up the ring (c15 < P),
; one power of two at a time.
.macro SHIFTBIT RA, RB, B
        candi   c13, c15, #(\B)
        bz      c13, shb\@
        rxl     \RA, \RA, #(\B)
        rxl     \RB, \RB, #(\B)
shb\@:
.endm
.macro SHIFTUP RA, RB
.set SB 1
.rept 17
.if SB < P
        SHIFTBIT \RA, \RB, SB
.endif
.set SB SB * 2
.endr
.endm
.macro SHIFTBIT1 RA, B
        candi   c13, c15, #(\B)
        bz      c13, shc\@
        rxl     \RA, \RA, #(\B)
shc\@:
.endm
.macro SHIFTUP1 RA
.set SB 1
.rept 17
.if SB < P
        SHIFTBIT1 \RA, SB
.endif
.set SB SB * 2
.endr
.endm

.macro RELAYOUT_CONSTS
        ; T = left PE (K_LEFT)
        ld      r13, [#K_LEFT]
        ceqi    r13, #1
.if MODE == 1
        SETK16  K_DLT, 1, (-1)
        SETK16  K_WRAP, (-P), P
.else
        SETK16  K_DLT, (-1), (-1)
        SETK16  K_WRAP, P, P
.endif
.endm

; RELAYOUT_IN g, which: segment g (assembly-time constant) of the batch;
; which = 0: both images at once (rows INL and INR), 1: the left image only,
; 2: the right image only (rows INL; used when two sets of rows do not fit).
.macro RELAYOUT_IN G, WHICH
.phase video_in
        ; load the batch's lines: row y = line c8 + y of the ROI
        cli     c10, #0
        cmov    c11, c9
        caddi   c12, c8, #Y0
        cli     c13, #(X0 + (\G) * P)
rli_v\@:
.if (\WHICH) == 0
        vin     #0, [c10 + INL], c12, c13
        vin     #1, [c10 + INR], c12, c13
.elif (\WHICH) == 1
        vin     #0, [c10 + INL], c12, c13
.else
        vin     #1, [c10 + INL], c12, c13
.endif
        caddi   c10, c10, #1
        caddi   c12, c12, #1
        loop    c11, rli_v\@
.phase relayout_in
        ; sender index u = p, receiver index xl = p (16 bit)
        pidx    r0, #0
        pidx    r1, #1
        mov     r2, r0
        mov     r3, r1
        ; X = g*P + p; R'/L' indices by kind (T = left PE)
        addi    r10, r0, #(((\G) * P) & 255)
        adci    r11, r1, #((((\G) * P) >> 8) & 255)
        ld      r13, [#K_LEFT]
        ceqi    r13, #1
.if MODE == 1
        li      r12, #(S & 255)
        li      r13, #((S >> 8) & 255)
        sub     r4, r12, r10
        sbc     r5, r13, r11                ; left R': s - X
        sub     r12, r10, r12
        sbc     r13, r11, r13               ; right R', L': X - s
        tsel    r4, r4, r12
        tsel    r5, r5, r13
        li      r12, #((S + D - 1) & 255)
        li      r13, #(((S + D - 1) >> 8) & 255)
        sub     r6, r12, r10
        sbc     r7, r13, r11                ; left L': s + D - 1 - X
        li      r12, #(S & 255)
        li      r13, #((S >> 8) & 255)
        sub     r12, r10, r12
        sbc     r13, r11, r13
        tsel    r6, r6, r12
        tsel    r7, r7, r13
.else
        addi    r4, r10, #1
        adci    r5, r11, #0                 ; R'[X + 1] = R[X]
        mov     r6, r4
        mov     r7, r5
.endif
        ld      r14, [#K_DLT]
        ld      r15, [#(K_DLT + 1)]
        cli     c15, #0
        cli     c14, #P
rli_r\@:
        ; sender: line ((p + t) mod P) >> LSH, if it is one of the batch's
        mov     r10, r0
        mov     r11, r1
.if LSH == 1
        shri    r11, r11, #1
        rorc    r10, r10
.endif
        lcb     r12, c9, #0
        lcb     r13, c9, #1
        sub     r12, r10, r12
        sbc     r13, r11, r13
        tc                                  ; T = line < lines in batch
        mif
        ldx     r8, [r10:r11 + INL]
.if (\WHICH) == 0
        ldx     r9, [r10:r11 + INR]
.endif
        mend
.if (\WHICH) == 0
        SHIFTUP r8, r9
.elif (\WHICH) == 2
        SHIFTUP1 r8
        mov     r9, r8
.else
        SHIFTUP1 r8
.endif
        ; receiver: store where the index is in range (unsigned 16 bit)
.if (\WHICH) != 1
        li      r12, #(LIMR & 255)
        li      r13, #((LIMR >> 8) & 255)
        sub     r12, r12, r4
        sbc     r13, r13, r5
        tc
        tnot
        mif
        stx     r9, [r4:r5 + IMGR]
        mend
.endif
.if (\WHICH) != 2
        li      r12, #(LIML & 255)
        li      r13, #((LIML >> 8) & 255)
        sub     r12, r12, r6
        sbc     r13, r13, r7
        tc
        tnot
        mif
        stx     r8, [r6:r7 + IMGL]
        mend
.endif
        ; u = (u + 1) mod P
        addi    r0, r0, #1
        adci    r1, r1, #0
        li      r12, #(P & 255)
        li      r13, #((P >> 8) & 255)
        sub     r12, r0, r12
        sbc     r13, r1, r13                ; C = u < P
        li      r13, #0
        csel    r0, r0, r13
        csel    r1, r1, r13
        ; xl = xl - 1 (mod P); indices follow X
        subi    r2, r2, #1
        sbci    r3, r3, #0
        setc    r12                         ; wrapped
        add     r4, r4, r14
        adc     r5, r5, r15
        add     r6, r6, r14
        adc     r7, r7, r15
        ceqi    r12, #1
        mif
        addi    r2, r2, #(P & 255)
        adci    r3, r3, #((P >> 8) & 255)
        ld      r10, [#K_WRAP]
        ld      r11, [#(K_WRAP + 1)]
        add     r4, r4, r10
        adc     r5, r5, r11
        add     r6, r6, r10
        adc     r7, r7, r11
        mend
        caddi   c15, c15, #1
        loop    c14, rli_r\@
.endm

; RELAYOUT_OUT g: segment g of the output lines of the batch. Rows OUT + y
; receive line y's pixels g*P .. g*P + P - 1 (one per PE); then `vout`
; writes the batch's output lines c10 .. c10 + c11 - 1 (batch-relative).
.macro RELAYOUT_OUT G
.phase relayout_out
        ; sender index u = p; receiver index xl = p
        pidx    r0, #0
        pidx    r1, #1
        mov     r2, r0
        mov     r3, r1
        cli     c15, #0
        cli     c14, #P
rlo_r\@:
        ; sender: output PE of a batch line, pixel g*P + u inside the ROI
        pidx    r10, #0
        pidx    r11, #1
.if LSH == 1
        andi    r12, r10, #1
        shri    r11, r11, #1
        rorc    r10, r10
.else
        li      r12, #1
.endif
        lcb     r4, c9, #0
        lcb     r5, c9, #1
        sub     r4, r10, r4
        sbc     r5, r11, r5
        setc    r13                         ; line < lines in batch
        and     r12, r12, r13
        li      r4, #((N - (\G) * P) & 255)
        li      r5, #(((N - (\G) * P) >> 8) & 255)
        sub     r6, r0, r4
        sbc     r7, r1, r5                  ; C = u < N - g*P
        setc    r13
        and     r12, r12, r13
        ceqi    r12, #1
        mif
        ldx     r8, [r0:r1 + (MAP + (\G) * P)]
        mend
        SHIFTUP1 r8
        ; receiver: source PE xl = (p - t) mod P; its line, if an output PE
        mov     r10, r2
        mov     r11, r3
.if LSH == 1
        andi    r12, r10, #1
        shri    r11, r11, #1
        rorc    r10, r10
.else
        li      r12, #1
.endif
        lcb     r4, c9, #0
        lcb     r5, c9, #1
        sub     r4, r10, r4
        sbc     r5, r11, r5
        setc    r13
        and     r12, r12, r13
        ceqi    r12, #1
        mif
        stx     r8, [r10:r11 + OUT]
        mend
        ; u = (u + 1) mod P; xl = (xl - 1) mod P
        addi    r0, r0, #1
        adci    r1, r1, #0
        li      r12, #(P & 255)
        li      r13, #((P >> 8) & 255)
        sub     r12, r0, r12
        sbc     r13, r1, r13
        li      r13, #0
        csel    r0, r0, r13
        csel    r1, r1, r13
        subi    r2, r2, #1
        sbci    r3, r3, #0
        setc    r12
        ceqi    r12, #1
        mif
        addi    r2, r2, #(P & 255)
        adci    r3, r3, #((P >> 8) & 255)
        mend
        caddi   c15, c15, #1
        loop    c14, rlo_r\@
        ; write the batch's output lines of this segment
.phase video_out
        cmov    c12, c10
        cadd    c13, c8, c10                ; ROI line of the first output line
        cli     c14, #((\G) * P)
        cmov    c15, c11
rlo_v\@:
        vout    #0, [c12 + OUT], c13, c14
        caddi   c12, c12, #1
        caddi   c13, c13, #1
        loop    c15, rlo_v\@
.endm

.equ BATCH_IDX 255                  ; param word holding the current batch

        cli     c0, #0
        cst     c0, [#BATCH_IDX]
batch:
        cld     c0, [#BATCH_IDX]
        cshli   c1, c0, #2
        cld     c8, [c1 + 1]                ; first ROI line of the batch
        cld     c9, [c1 + 2]                ; lines in the batch
        DP_SETUP
        RELAYOUT_CONSTS
.set GI 0
.rept NSEG
.if SPLIT_IN
        RELAYOUT_IN GI, 1
        RELAYOUT_IN GI, 2
.else
        RELAYOUT_IN GI, 0
.endif
.set GI GI + 1
.endr
        DP_INIT
        DP_FORWARD
.phase backtrack
        DP_CLEARMAP
        DP_BACKTRACK
        DP_MERGE
        cld     c0, [#BATCH_IDX]
        cshli   c1, c0, #2
        cld     c10, [c1 + 3]               ; first output line (batch-relative)
        cld     c11, [c1 + 4]               ; output lines
.set GI 0
.rept NSEG
        RELAYOUT_OUT GI
.set GI GI + 1
.endr
        cld     c0, [#BATCH_IDX]
        caddi   c0, c0, #1
        cst     c0, [#BATCH_IDX]
        cld     c1, [#0]
        blt     c0, c1, batch
        halt
