; .rept with a .set counter, .if / .elif / .else, .ifdef / .ifndef
.equ WIDTH 4
.set K 0
.rept WIDTH
  .if K == 0
        li r0, #K
  .elif K % 2
        addi r0, r0, #(K * 3)
  .else
        subi r0, r0, #1
  .endif
  .set K K + 1
.endr
.ifdef WIDTH
        st r0, [#(WIDTH * 2)]
.endif
.ifndef UNDEFINED_NAME
        cli c1, #((1 << 4) | 0x3 ^ 0b1)
.else
.error "not reached"
.endif
.if !(WIDTH > 8) && (WIDTH != 3 || 0)
        cli c2, #-(~5)
.endif
        halt
