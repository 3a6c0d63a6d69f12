# isa.cli_asm: `imapsim asm` / `imapsim disasm` end to end.
#   cmake -DIMAPSIM=<path> -DWORK=<scratch dir> -P cli_asm.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/inc.s ".macro acc dst, src\n  cadd \\dst, \\dst, \\src\n.endm\n")
file(WRITE ${WORK}/fw.s [=[
.include "inc.s"
.ifndef N
.equ N 10
.endif
.phase sum
        cli c0, #N
        cli c1, #0
top:    acc c1, c0
        loop c0, top
        halt
]=])
file(WRITE ${WORK}/bad.s "nop\n  frob r1\nli r1, #300\n")

function(run expect_rc)
  execute_process(COMMAND ${IMAPSIM} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL expect_rc)
    message(FATAL_ERROR "imapsim ${ARGN}: exit ${rc}, expected ${expect_rc}\n${out}\n${err}")
  endif()
  set(OUT "${out}" PARENT_SCOPE)
  set(ERR "${err}" PARENT_SCOPE)
endfunction()

run(0 asm ${WORK}/fw.s -o ${WORK}/fw.bin -D N=7 --listing ${WORK}/fw.lst)
run(0 disasm ${WORK}/fw.bin -o ${WORK}/fw.txt)
run(0 asm ${WORK}/fw.txt -o ${WORK}/fw2.bin)
run(0 disasm ${WORK}/fw.bin --no-comments)
set(a "${OUT}")
run(0 disasm ${WORK}/fw2.bin --no-comments)
if(NOT a STREQUAL OUT)
  message(FATAL_ERROR "disassemble -> assemble changed the code:\n${a}\n---\n${OUT}")
endif()
if(NOT a MATCHES "cli c0, #7")
  message(FATAL_ERROR "-D N=7 not applied:\n${a}")
endif()

run(2 asm ${WORK}/bad.s -o ${WORK}/bad.bin)
if(EXISTS ${WORK}/bad.bin)
  message(FATAL_ERROR "a failed assembly wrote its output")
endif()
if(NOT ERR MATCHES "bad.s:2:3: error: unknown instruction 'frob'" OR
   NOT ERR MATCHES "bad.s:3:9: error: immediate 300 out of range")
  message(FATAL_ERROR "diagnostics missing:\n${ERR}")
endif()
run(2 asm ${WORK}/fw.s -o ${WORK}/x.bin -D 1N=3)
file(WRITE ${WORK}/trunc.bin "IMAPFW01abc")
run(2 disasm ${WORK}/trunc.bin)
if(NOT ERR MATCHES "truncated")
  message(FATAL_ERROR "truncated file not reported:\n${ERR}")
endif()
file(REMOVE_RECURSE ${WORK})
