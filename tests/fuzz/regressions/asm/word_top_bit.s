; disassembler: a word with bit 63 set came out as `.word 0xffff...`, a
; number the assembler refuses (too large for signed 64-bit), so the
; disassembly did not re-assemble; it is now written `.word ~0x...`
        .word -1
        .word (1 << 63)
        .word 0x7fffffffffffffff
        halt
