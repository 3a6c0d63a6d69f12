; broadcast, per-PE and external memory
        cli c1, #8
        li r0, #200
        st r0, [c1]
        st r0, [c1 + 4]
        ld r1, [c1 - 4 + 8]
        ld r2, [#12]
        pidx r3, #0
        li r4, #0
        stx r3, [r3 + 20]
        ldx r5, [r3:r4 + 20]
        cli c2, #1
        ldx r6, [r3 + c2 + 19]
        cli c3, #0
        cli c4, #16
        xst [#0], ext[c3], c4
        xld [c1 + 24], ext[c3], c4
        halt
