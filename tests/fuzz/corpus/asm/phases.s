; phases, register aliases, raw words, several labels on a line
.defphase setup
.reg acc, r7
.reg ptr, c4
.phase setup
        cli ptr, #1
        li acc, #1
.phase compute
a: b:   shli acc, acc, #1
        shri r8, acc, #7
        rolc r9, acc
        rorc r10, r9
        shlv r11, acc, r8
        shrv r12, acc, r8
        lc r13, ptr
        lcb r14, ptr, #1
        csel r15, r13, r14
        tsel r15, r15, r13
        mini r1, r15, #9
        maxi r2, r1, #-1
        adc r3, r1, r2
        sbc r4, r3, r1
        sbci r5, r4, #1
        adci r6, r5, #2
        min r1, r2, r3
        max r1, r2, r3
        and r1, r2, r3
        or r1, r2, r3
        xor r1, r2, r3
        andi r1, r1, #15
        ori r1, r1, #16
        cne r1, r2
        cleu r1, r2
        cgtu r1, r2
        cgeu r1, r2
        cltu r1, r2
        cnei r1, #3
        cleui r1, #3
        cgtui r1, #3
        cgeui r1, #3
        mov r0, acc
        .word 0x0000000000000000
.phase setup
        nop
        halt
