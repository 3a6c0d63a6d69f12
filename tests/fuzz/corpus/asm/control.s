; CP arithmetic, calls, branches, the param block
        cli c0, #5
        cli c1, #0
        call body
        cst c1, [#3]
        cld c5, [#3]
        cli c6, #7
        bne c5, c6, skip
        csubi c5, c5, #1
skip:   blt c1, c0, done
        bge c0, c1, done
        beq c0, c0, done
done:   cshli c7, c0, #2
        cshri c8, c7, #1
        csrai c9, c8, #31
        cand c10, c7, c8
        cor c11, c7, c8
        cxori c12, c11, #0xff
        cmov c13, c12
        bz c14, end
        jmp end
body:   cadd c1, c1, c0
        bnz c0, b2
b2:     ret
end:    halt
