; The DP forward pass as a straightforward compiler for the 1DC language
; would plausibly emit it for this machine (docs/firmware.md, section 8):
; every C variable lives in memory (NB-byte ints, loaded and stored around
; every statement), every `if` is a masked conditional (mif / mend), the
; level loop is not unrolled, all D levels of every column are computed
; (the bounding box), one byte per pointer. It is a measurement aid, not
; part of the product firmware: imapsim exec firmware/asm/demo/compiled_node.s
; -D NB=2 runs K columns of D levels and reports the cycles.
.ifndef NB
.equ NB 2                           ; bytes per int
.endif
.ifndef D
.equ D 64
.endif
.ifndef K
.equ K 8
.endif
.equ KM 8
.equ KB 1
.equ GB 64
.equ WO 100
.equ WD 100
; memory (per PE): variables, then arrays
.equ VA 0                           ; int a
.equ VB VA + NB                     ; int b
.equ VDIFF VB + NB
.equ VMN VDIFF + NB
.equ VG VMN + NB
.equ VM VG + NB
.equ VD VM + NB
.equ VO VD + NB
.equ VBEST VO + NB
.equ VP VBEST + NB                  ; char p
.equ EPREV VP + 1                   ; int Eprev[D + 1]
.equ ECUR EPREV + (D + 1) * NB      ; int Ecur[D + 1]
.equ RLINE ECUR + (D + 1) * NB      ; uchar R[K + 1]
.equ LLINE RLINE + K + 1            ; uchar L[K + D + 1]
.equ PTR LLINE + K + D + 1          ; uchar ptr[K][D] (one column kept: D bytes)

; Two int registers: A = r0.. (low byte first), B = r4.. ; NB is 2 or 4.
.macro LDINT R0, R1, R2, R3, BASE, OFF
        ld      \R0, [\BASE + (\OFF)]
        ld      \R1, [\BASE + ((\OFF) + 1)]
.if NB == 4
        ld      \R2, [\BASE + ((\OFF) + 2)]
        ld      \R3, [\BASE + ((\OFF) + 3)]
.endif
.endm
.macro STINT R0, R1, R2, R3, BASE, OFF
        st      \R0, [\BASE + (\OFF)]
        st      \R1, [\BASE + ((\OFF) + 1)]
.if NB == 4
        st      \R2, [\BASE + ((\OFF) + 2)]
        st      \R3, [\BASE + ((\OFF) + 3)]
.endif
.endm
.macro LDA BASE, OFF
        LDINT     r0, r1, r2, r3, \BASE, \OFF
.endm
.macro LDB BASE, OFF
        LDINT     r4, r5, r6, r7, \BASE, \OFF
.endm
.macro STA BASE, OFF
        STINT     r0, r1, r2, r3, \BASE, \OFF
.endm
.macro STB BASE, OFF
        STINT     r4, r5, r6, r7, \BASE, \OFF
.endm
.macro ADDAB                        ; A += B
        add     r0, r0, r4
        adc     r1, r1, r5
.if NB == 4
        adc     r2, r2, r6
        adc     r3, r3, r7
.endif
.endm
.macro ADDAA                        ; A += A
        add     r0, r0, r0
        adc     r1, r1, r1
.if NB == 4
        adc     r2, r2, r2
        adc     r3, r3, r3
.endif
.endm
.macro SUBAB                        ; A -= B
        sub     r0, r0, r4
        sbc     r1, r1, r5
.if NB == 4
        sbc     r2, r2, r6
        sbc     r3, r3, r7
.endif
.endm
.macro SUBBA                        ; B -= A
        sub     r4, r4, r0
        sbc     r5, r5, r1
.if NB == 4
        sbc     r6, r6, r2
        sbc     r7, r7, r3
.endif
.endm
.macro LIA V
        li      r0, #((\V) & 255)
        li      r1, #(((\V) >> 8) & 255)
.if NB == 4
        li      r2, #(((\V) >> 16) & 255)
        li      r3, #(((\V) >> 24) & 255)
.endif
.endm
.macro LIB V
        li      r4, #((\V) & 255)
        li      r5, #(((\V) >> 8) & 255)
.if NB == 4
        li      r6, #(((\V) >> 16) & 255)
        li      r7, #(((\V) >> 24) & 255)
.endif
.endm
.macro TNEGA                        ; T = A < 0
.if NB == 4
        cgeui   r3, #128
.else
        cgeui   r1, #128
.endif
.endm

        ; Eprev = start column (j * Wo), Ecur[-1] handled by the j == 0 branch
        cli     c15, #0
        cli     c0, #1
kcol:
        ; a = R[k] (an int)
        LIA     0
        ld      r0, [c0 + RLINE]
        STA     c15, VA
        cli     c1, #0                      ; j
        cadd    c2, c0, c1                  ; k + j
jlev:
        ; b = L[k + j]
        LIB     0
        ld      r4, [c2 + LLINE]
        STB     c15, VB
        ; diff = a - b; if (diff < 0) diff = -diff
        LDA     c15, VA
        LDB     c15, VB
        SUBAB
        STA     c15, VDIFF
        LDA     c15, VDIFF
        TNEGA
        mif
        LIB     0
        SUBBA
        STB     c15, VDIFF
        mend
        ; mn = a < b ? a : b
        LDA     c15, VA
        LDB     c15, VB
        SUBAB
        TNEGA
        mif
        LDA     c15, VA
        STA     c15, VMN
        melse
        LDB     c15, VB
        STB     c15, VMN
        mend
        ; g = gb - mn; if (g < 0) g = 0
        LIA     GB
        LDB     c15, VMN
        SUBAB
        STA     c15, VG
        LDA     c15, VG
        TNEGA
        mif
        LIA     0
        STA     c15, VG
        mend
        ; m = Eprev[j] + km * diff + kb * g   (km = 8: three doublings, kb = 1)
        LDA     c15, VDIFF
        ADDAA
        ADDAA
        ADDAA
        LDB     c15, VG
        ADDAB
        cshli   c3, c1, #(NB / 2)
        LDB     c3, EPREV
        ADDAB
        STA     c15, VM
        ; d = Eprev[j + 1] + Wd
        LDA     c3, (EPREV + NB)
        LIB     WD
        ADDAB
        STA     c15, VD
        ; best = m; p = 0
        LDA     c15, VM
        STA     c15, VBEST
        li      r0, #0
        st      r0, [#VP]
        ; if (d < best) { best = d; p = 1; }
        LDA     c15, VD
        LDB     c15, VBEST
        SUBAB
        TNEGA
        mif
        LDA     c15, VD
        STA     c15, VBEST
        li      r0, #1
        st      r0, [#VP]
        mend
        ; if (j > 0) { o = Ecur[j - 1] + Wo; if (o < best) { best = o; p = 2; } }
        bz      c1, nooc
        LDA     c3, (ECUR - NB)
        LIB     WO
        ADDAB
        STA     c15, VO
        LDA     c15, VO
        LDB     c15, VBEST
        SUBAB
        TNEGA
        mif
        LDA     c15, VO
        STA     c15, VBEST
        li      r0, #2
        st      r0, [#VP]
        mend
nooc:
        ; Ecur[j] = best; ptr[k][j] = p
        LDA     c15, VBEST
        STA     c3, ECUR
        ld      r0, [#VP]
        st      r0, [c1 + PTR]
        caddi   c1, c1, #1
        caddi   c2, c2, #1
        cli     c4, #D
        blt     c1, c4, jlev
        ; Eprev = Ecur (arrays in the PE memory)
        cli     c1, #0
cpy:
        cshli   c3, c1, #(NB / 2)
        LDA     c3, ECUR
        STA     c3, EPREV
        caddi   c1, c1, #1
        cli     c4, #D
        blt     c1, c4, cpy
        caddi   c0, c0, #1
        cli     c4, #(K + 1)
        blt     c0, c4, kcol
        halt
